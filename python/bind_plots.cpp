// gpm._plots: the plot() methods of gpm.CalibrationResult and gpm.Simulation.
// Their code is pure Python (python/plots.py, matplotlib), carried in the
// module as text (python/CMakeLists.txt) and run into the submodule here; it
// sets the methods on the classes. matplotlib is imported only when a plot is made.
#include <pybind11/pybind11.h>

#include "python/bindings.hpp"

namespace gpm::python {

extern const char* const kPlotsSource;
extern const char* const kPlotsFile;

void bind_plots(pybind11::module_& m) { exec_submodule(m, "_plots", kPlotsSource, kPlotsFile); }

}  // namespace gpm::python
