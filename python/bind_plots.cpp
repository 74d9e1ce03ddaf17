// gpm._plots: the plot() methods of gpm.CalibrationResult and gpm.Simulation.
// Their code is pure Python (python/plots.py, matplotlib), carried in the
// module as text (python/CMakeLists.txt) and run into the submodule here; it
// sets the methods on the classes. matplotlib is imported only when a plot is made.
#include <pybind11/pybind11.h>

#include "python/bindings.hpp"

namespace gpm::python {

extern const char* const kPlotsSource;
extern const char* const kPlotsFile;

void bind_plots(pybind11::module_& m) {
  namespace py = pybind11;
  py::module_ plots = m.def_submodule("_plots");
  py::dict ns = plots.attr("__dict__");
  ns["__file__"] = kPlotsFile;
  ns["_gpm"] = m;
  const py::module_ builtins = py::module_::import("builtins");
  builtins.attr("exec")(builtins.attr("compile")(kPlotsSource, kPlotsFile, "exec"), ns);
}

}  // namespace gpm::python
