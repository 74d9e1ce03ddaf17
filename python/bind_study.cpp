// gpm.study: the population study on local threads or a Dask cluster. Its
// code is pure Python (python/study.py), carried in the module as text
// (python/CMakeLists.txt) and run into the submodule here, which is also
// registered as sys.modules["gpm.study"] so that `import gpm.study` works and
// Dask workers find its functions by name.
#include <pybind11/pybind11.h>

#include "python/bindings.hpp"

namespace gpm::python {

extern const char* const kStudySource;
extern const char* const kStudyFile;

void bind_study(pybind11::module_& m) {
  namespace py = pybind11;
  py::module_ study = m.def_submodule("study");
  py::dict ns = study.attr("__dict__");
  ns["__file__"] = kStudyFile;
  ns["_gpm"] = m;  // the module being built (not yet importable by name)
  const py::module_ builtins = py::module_::import("builtins");
  builtins.attr("exec")(builtins.attr("compile")(kStudySource, kStudyFile, "exec"), ns);
  py::module_::import("sys").attr("modules")["gpm.study"] = study;
}

}  // namespace gpm::python
