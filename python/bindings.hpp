// The parts of the gpm Python module, one per layer it exposes.
#pragma once

#include <pybind11/pybind11.h>

namespace gpm::python {

// gpm.Robot, load_robot, read_samples, models_dir, scenarios_dir.
void bind_robot(pybind11::module_& m);

// gpm.calibrate, CalibrationResult, load_result.
void bind_calibrate(pybind11::module_& m);

// gpm.design, Design, pose_bounds, crb.
void bind_design(pybind11::module_& m);

// gpm.simulate, Simulation.
void bind_simulate(pybind11::module_& m);

// gpm.run, population_robot_scenario, scenario_seed.
void bind_run(pybind11::module_& m);

// gpm.study (python/study.py): needs bind_run's functions.
void bind_study(pybind11::module_& m);

// gpm._plots (python/plots.py): CalibrationResult.plot and Simulation.plot;
// needs bind_calibrate's and bind_simulate's classes.
void bind_plots(pybind11::module_& m);
// Runs Python source (named file in tracebacks) into submodule `name` of m,
// with _gpm bound to m (the module being built); returns the submodule.
pybind11::module_ exec_submodule(pybind11::module_& m, const char* name, const char* source, const char* file);

}  // namespace gpm::python
