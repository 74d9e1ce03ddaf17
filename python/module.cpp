// The gpm Python module: the toolkit's library (robot model, kinematics,
// calibration, excitation design, Cramer-Rao bounds, the MuJoCo twin) on
// NumPy arrays. Errors (python/errors.hpp): gpm::InputError -> gpm.InputError
// (a ValueError) with the library's message in Python's words (keywords for
// flags); an argument of the wrong type -> gpm.InputTypeError (also a
// TypeError); sim::SimError -> gpm.SimError and any other gpm::Error ->
// gpm.Error (RuntimeErrors).
#include <string>

#include <pybind11/pybind11.h>

#include "models/parameters.hpp"
#include "python/allocator.hpp"
#include "python/bindings.hpp"
#include "python/errors.hpp"

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
conditioning. Bad input raises gpm.InputError (a ValueError; an argument of
the wrong type gpm.InputTypeError, also a TypeError), naming the keyword.
)doc";
  gpm::python::register_errors(m);
  // True where the environment had frozen glibc's mmap threshold (a Dask worker) and the import raised it.
  m.attr("_large_blocks_on_the_heap") = gpm::python::keep_large_blocks_on_the_heap();

  py::list names;
  for (int i = 0; i < gpm::kNumParams; ++i) names.append(std::string(gpm::param_name(i)));
  m.attr("PARAM_NAMES") = py::tuple(names);

  gpm::python::bind_robot(m);
  gpm::python::bind_calibrate(m);
  gpm::python::bind_design(m);
  gpm::python::bind_simulate(m);
  gpm::python::bind_run(m);
  gpm::python::bind_study(m);
  gpm::python::bind_plots(m);
}
