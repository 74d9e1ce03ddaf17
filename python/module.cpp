// The gpm Python module: the toolkit's library (robot model, kinematics,
// calibration, excitation design, Cramer-Rao bounds, the MuJoCo twin) on
// NumPy arrays. Errors: gpm::InputError -> gpm.InputError (a ValueError) with
// the command line's message; sim::SimError -> gpm.SimError (a RuntimeError);
// any other gpm::Error -> gpm.Error (a RuntimeError).
#include <string>

#include <pybind11/pybind11.h>

#include "models/errors.hpp"
#include "models/parameters.hpp"
#include "python/bindings.hpp"
#include "sim/mujoco_util.hpp"

namespace py = pybind11;

PYBIND11_MODULE(gpm, m) {
  m.doc() = R"doc(
gpm: calibration toolkit of the Googol GPM2002 planar 3-RRR parallel
manipulator (millimetres and radians).

  robot = gpm.load_robot()                   # nominal GPM2002
  readings = gpm.read_samples("samples.csv") # (n, 3) encoder readings
  result = gpm.calibrate(readings, robot)    # ML cost, Ceres LM
  result.geometry, result.std, result.diagnostics, result.save("result.yaml")

Also: gpm.run(scenario) (the whole `gpm run`), gpm.study.population (a
population of robots on local threads or a Dask cluster),
gpm.simulate(scenario) (MuJoCo twin), gpm.design (calibration poses),
gpm.crb and gpm.pose_bounds (Cramer-Rao bounds), Robot.ik / fk / jacobian /
conditioning. Bad input raises gpm.InputError (a ValueError).
)doc";
  // Registered base first: pybind11 tries the most recent translator first.
  py::register_exception<gpm::Error>(m, "Error", PyExc_RuntimeError);
  py::register_exception<gpm::InputError>(m, "InputError", PyExc_ValueError);
  py::register_exception<gpm::sim::SimError>(m, "SimError", PyExc_RuntimeError);

  py::list names;
  for (int i = 0; i < gpm::kNumParams; ++i) names.append(std::string(gpm::param_name(i)));
  m.attr("PARAM_NAMES") = py::tuple(names);

  gpm::python::bind_robot(m);
  gpm::python::bind_calibrate(m);
  gpm::python::bind_design(m);
  gpm::python::bind_simulate(m);
  gpm::python::bind_run(m);
  gpm::python::bind_study(m);
}
