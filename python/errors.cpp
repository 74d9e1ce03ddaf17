#include "python/errors.hpp"

#include <cmath>
#include <regex>
#include <vector>

#include <fmt/format.h>

#include "sim/mujoco_util.hpp"

namespace gpm::python {

namespace py = pybind11;

namespace {

// How a flag reads in Python: a keyword, a keyword with its value (cost="ml",
// fix=["xa1", "ya1"]), a boolean keyword (name=True), or none (the command
// line's own flag, named as such).
enum class Kind { kName, kText, kList, kBool, kCommandOnly };

struct Word {
  const char* flag;
  const char* key;
  Kind kind;
  const char* values;  // kText: the flag's values, a regex alternation
};

// The flags the library's messages name (calib/, models/, the checks of gpm
// calibrate and gpm design) and the keyword of gpm.calibrate / gpm.design for each.
const Word kWords[] = {
    {"allow-rank-deficient", "allow_rank_deficient", Kind::kBool, ""},
    {"static", "static_model", Kind::kBool, ""},
    {"fix", "fix", Kind::kList, ""},
    {"cost", "cost", Kind::kText, "j1|j2|j3|ml"},
    {"method", "method", Kind::kText, "de\\+lm|lm|ga|pso|de"},
    {"criterion", "criterion", Kind::kText, "d|worst|positioning"},
    {"model", "robot", Kind::kName, ""},
    {"data", "readings", Kind::kName, ""},
    {"sigma", "sigma", Kind::kName, ""},
    {"budget", "budget", Kind::kName, ""},
    {"seed", "seed", Kind::kName, ""},
    {"encoder-bits", "encoder_bits", Kind::kName, ""},
    {"count", "count", Kind::kName, ""},
    {"grid-step", "grid_step", Kind::kName, ""},
    {"guard", "guard", Kind::kName, ""},
    {"loss", "", Kind::kCommandOnly, ""},
    {"reference-point", "", Kind::kCommandOnly, ""},
};

// fix=["xa1", "ya1"] of the list "xa1,ya1".
std::string python_list(const std::string& list) {
  std::string out = "[";
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = list.find(',', start);
    out += (start ? ", \"" : "\"") + list.substr(start, comma - start) + "\"";
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out + "]";
}

// One flag of w replaced in text (text holds no quoted command). A flag
// starts the text or follows a space, bracket or quote (not a path's "a--b")
// and ends before anything but a letter, digit or hyphen (--fix, not --fixed).
std::string replace_flag(const std::string& text, const Word& w) {
  const std::string flag = std::string("(^|[\\s(\\[`'\"])--") + w.flag;
  const std::string end = "(?![a-z0-9-])";
  const std::string key = std::string("$1") + w.key;
  switch (w.kind) {
    case Kind::kBool:
      return std::regex_replace(text, std::regex(flag + end), key + "=True");
    case Kind::kCommandOnly:
      return std::regex_replace(text, std::regex(flag + end), "$1gpm calibrate --" + std::string(w.flag));
    case Kind::kText: {
      const std::string valued =
          std::regex_replace(text, std::regex(flag + " (" + w.values + ")" + end), key + "=\"$2\"");
      return std::regex_replace(valued, std::regex(flag + end), key);
    }
    case Kind::kList: {
      std::string out;
      const std::regex list(flag + " ([a-z0-9]+(?:,[a-z0-9]+)*)" + end);
      std::size_t last = 0;
      for (auto it = std::sregex_iterator(text.begin(), text.end(), list); it != std::sregex_iterator(); ++it) {
        out += text.substr(last, static_cast<std::size_t>(it->position()) - last);
        out += (*it)[1].str() + w.key + "=" + python_list((*it)[2].str());
        last = static_cast<std::size_t>(it->position() + it->length());
      }
      out += text.substr(last);
      return std::regex_replace(out, std::regex(flag + end), key);
    }
    case Kind::kName:
      break;
  }
  return std::regex_replace(text, std::regex(flag + end), key);
}

// Every flag of kWords replaced in text (text holds no quoted command).
std::string translate_plain(std::string text) {
  if (text.find("--") == std::string::npos) return text;
  for (const Word& w : kWords) text = replace_flag(text, w);
  return text;
}

PyObject* g_error = nullptr;
PyObject* g_input_error = nullptr;
PyObject* g_input_type_error = nullptr;
PyObject* g_sim_error = nullptr;

// A new exception class gpm.NAME with the given bases, set on m.
PyObject* new_exception(py::module_& m, const char* name, const py::tuple& bases, const char* doc) {
  PyObject* type = PyErr_NewExceptionWithDoc((std::string("gpm.") + name).c_str(), doc, bases.ptr(), nullptr);
  if (!type) throw py::error_already_set();
  m.attr(name) = py::reinterpret_borrow<py::object>(type);  // the module keeps one reference for ever
  return type;
}

}  // namespace

std::string python_words(std::string_view message) {
  // A quoted command (`gpm design --count 12`, gpm run --hardware) is the
  // command line's: its flags stay.
  static const std::regex command("`?gpm [a-z]+(?: [a-z]+)*(?: --?[a-z][a-z-]*(?: [^\\s;,()`]+)?)+`?");
  const std::string text(message);
  std::string out;
  std::size_t last = 0;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), command); it != std::sregex_iterator(); ++it) {
    out += translate_plain(text.substr(last, static_cast<std::size_t>(it->position()) - last)) + it->str();
    last = static_cast<std::size_t>(it->position() + it->length());
  }
  return out + translate_plain(text.substr(last));
}

void register_errors(py::module_& m) {
  g_error = new_exception(m, "Error", py::make_tuple(py::handle(PyExc_RuntimeError)),
                          "Root of the toolkit's errors (a RuntimeError).");
  g_input_error = new_exception(m, "InputError", py::make_tuple(py::handle(PyExc_ValueError)),
                                "Bad input (a ValueError): the message names the argument, file or key, what is "
                                "wrong and what would be valid.");
  g_input_type_error = new_exception(
      m, "InputTypeError", py::make_tuple(py::handle(g_input_error), py::handle(PyExc_TypeError)),
      "An argument of the wrong type: a gpm.InputError and a TypeError naming the keyword and the type it takes.");
  g_sim_error = new_exception(m, "SimError", py::make_tuple(py::handle(g_error)),
                              "The physics of the twin diverged (a gpm.Error, a RuntimeError).");
  m.def("_python_words", [](const std::string& message) { return python_words(message); }, py::arg("message"),
        "The library's message in Python's words (keywords for command-line flags); for tests.");
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputTypeError& e) {
      PyErr_SetString(g_input_type_error, python_words(e.what()).c_str());
    } catch (const InputError& e) {
      PyErr_SetString(g_input_error, python_words(e.what()).c_str());
    } catch (const sim::SimError& e) {
      PyErr_SetString(g_sim_error, e.what());
    } catch (const Error& e) {
      PyErr_SetString(g_error, e.what());
    }
  });
}

std::string type_name(const py::handle& v) {
  const py::handle type = py::type::of(v);
  const std::string module = py::str(type.attr("__module__"));
  const std::string name = py::str(type.attr("__qualname__"));
  return module == "builtins" ? name : module + "." + name;
}

long long whole_arg(const py::handle& v, std::string_view name, const Bound& b) {
  const bool number = !PyBool_Check(v.ptr()) && (PyLong_Check(v.ptr()) || PyFloat_Check(v.ptr()) ||
                                                  py::hasattr(v, "__index__"));
  if (!number)
    throw InputTypeError(fmt::format("{}: expected {}, got {}", name, describe(b), type_name(v)));
  if (PyFloat_Check(v.ptr())) return static_cast<long long>(check_bound(PyFloat_AsDouble(v.ptr()), b, name));
  const auto i = py::reinterpret_steal<py::object>(PyNumber_Index(v.ptr()));
  if (!i) throw py::error_already_set();
  const std::string text = py::str(i);
  int overflow = 0;
  const long long x = PyLong_AsLongLongAndOverflow(i.ptr(), &overflow);
  if (overflow != 0) check_bound(overflow > 0 ? HUGE_VAL : -HUGE_VAL, b, name, text);  // throws
  check_bound(static_cast<double>(x), b, name, text);
  if (static_cast<double>(x) >= b.hi && x > static_cast<long long>(b.hi)) check_bound(HUGE_VAL, b, name, text);
  return x;
}

std::string text_arg(const py::handle& v, std::string_view name, std::string_view valid) {
  if (!py::isinstance<py::str>(v))
    throw InputTypeError(fmt::format("{}: expected a str, {}, got {}", name, valid, type_name(v)));
  return v.cast<std::string>();
}

bool flag_arg(const py::handle& v, std::string_view name) {
  if (PyBool_Check(v.ptr())) return v.ptr() == Py_True;
  if (type_name(v) == "numpy.bool_") return PyObject_IsTrue(v.ptr()) == 1;
  throw InputTypeError(fmt::format("{}: expected True or False, got {}", name, type_name(v)));
}

double number_arg(const py::handle& v, std::string_view name, const Bound& b) {
  const bool number = !PyBool_Check(v.ptr()) && !py::isinstance<py::str>(v) && !PyComplex_Check(v.ptr()) &&
                      (PyLong_Check(v.ptr()) || PyFloat_Check(v.ptr()) || py::hasattr(v, "__float__"));
  if (!number)
    throw InputTypeError(fmt::format("{}: expected {}, got {}", name, describe(b), type_name(v)));
  const double x = PyFloat_AsDouble(v.ptr());
  if (x == -1.0 && PyErr_Occurred()) {  // an int beyond a double
    PyErr_Clear();
    return check_bound(HUGE_VAL, b, name, std::string(py::str(v)));
  }
  return check_bound(x, b, name);
}

}  // namespace gpm::python
