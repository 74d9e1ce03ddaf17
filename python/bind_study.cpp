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

pybind11::module_ exec_submodule(pybind11::module_& m, const char* name, const char* source, const char* file) {
  namespace py = pybind11;
  py::module_ sub = m.def_submodule(name);
  py::dict ns = sub.attr("__dict__");
  ns["__file__"] = file;
  ns["_gpm"] = m;  // the module being built (not yet importable by name)
  const py::module_ builtins = py::module_::import("builtins");
  builtins.attr("exec")(builtins.attr("compile")(source, file, "exec"), ns);
  return sub;
}

void bind_study(pybind11::module_& m) {
  pybind11::module_ study = exec_submodule(m, "study", kStudySource, kStudyFile);
  pybind11::module_::import("sys").attr("modules")["gpm.study"] = study;
}

}  // namespace gpm::python
