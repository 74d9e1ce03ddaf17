#include "python/convert.hpp"

#include <cmath>
#include <string_view>

#include <fmt/format.h>

#include "models/errors.hpp"
#include "python/errors.hpp"

namespace gpm::python {

py::dict geometry_dict(const Geometry& g) {
  py::dict d;
  for (int i = 0; i < kNumParams; ++i) d[py::str(std::string(param_name(i)))] = g[i];
  return d;
}

Geometry geometry_from_dict(const py::dict& d, const Geometry& base, const std::string& what) {
  Geometry g = base;
  for (const auto& [key, value] : d) {
    const std::string name = py::str(key);
    const auto idx = param_index(name);
    if (!idx) {
      throw InputError(fmt::format("{}: unknown parameter '{}' (did you mean {}?); valid: xa1 ya1 xa2 ya2 xa3 "
                                   "ya3 la1 la2 la3 lb1 lb2 lb3 dth1 dth2 dth3",
                                   what, name, nearest_param_name(name)));
    }
    if (!py::isinstance<py::float_>(value) && !py::isinstance<py::int_>(value) &&
        !py::hasattr(value, "__float__"))
      throw InputTypeError(fmt::format("{}: {} must be a number in mm or rad, got {}", what, name, type_name(value)));
    const double v = value.cast<double>();
    if (!std::isfinite(v)) throw InputError(fmt::format("{}: {} must be a finite number, got {}", what, name, v));
    g[*idx] = v;
  }
  return g;
}

FreeMask param_set(const py::object& names, const std::string& what) {
  if (names.is_none()) return FreeMask{};
  if (py::isinstance<py::str>(names)) return parse_param_list(names.cast<std::string>(), what);
  if (!py::isinstance<py::iterable>(names))
    throw InputTypeError(fmt::format("{}: expected a list of parameter names (e.g. [\"xa1\", \"ya1\"]) or one "
                                     "comma-separated str, got {}", what, type_name(names)));
  std::string list;
  bool first = true;
  for (const auto& item : names) {
    if (!py::isinstance<py::str>(item))
      throw InputTypeError(fmt::format("{}: expected parameter names (str), got {}", what, type_name(item)));
    if (!first) list += ",";
    list += item.cast<std::string>();
    first = false;
  }
  return parse_param_list(list, what);
}

Robot robot_arg(const py::handle& v, const std::string& what) {
  if (!py::isinstance<Robot>(v))
    throw InputTypeError(fmt::format("{}: expected a gpm.Robot (gpm.load_robot(path) or gpm.Robot()), got {}", what,
                                     type_name(v)));
  return v.cast<Robot>();
}

py::list param_names(const FreeMask& mask) {
  py::list out;
  for (int i = 0; i < kNumParams; ++i)
    if (mask.test(static_cast<size_t>(i))) out.append(std::string(param_name(i)));
  return out;
}

namespace {

// A C-contiguous float64 (n, cols) array of a; a (cols,) vector becomes (1, cols).
py::array_t<double, py::array::c_style> rows_array(const py::handle& a, size_t cols, const std::string& what,
                                                   const char* example) {
  auto arr = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
  if (!arr) {
    PyErr_Clear();
    throw InputTypeError(fmt::format("{}: expected an array of numbers of shape (n, {}), e.g. {}, got {}", what, cols,
                                     example, type_name(a)));
  }
  if (arr.ndim() == 1 && static_cast<size_t>(arr.shape(0)) == cols) arr = arr.reshape({py::ssize_t{1}, static_cast<py::ssize_t>(cols)});
  if (arr.ndim() != 2 || static_cast<size_t>(arr.shape(1)) != cols) {
    std::string shape = "(";
    for (py::ssize_t k = 0; k < arr.ndim(); ++k) shape += (k ? ", " : "") + std::to_string(arr.shape(k));
    shape += arr.ndim() == 1 ? ",)" : ")";
    throw InputError(fmt::format("{}: expected shape (n, {}), got {}", what, cols, shape));
  }
  const double* p = arr.data();
  for (py::ssize_t k = 0; k < arr.size(); ++k)
    if (!std::isfinite(p[k]))
      throw InputError(fmt::format("{}: row {} column {} is {}; expected finite numbers", what,
                                   k / static_cast<py::ssize_t>(cols), k % static_cast<py::ssize_t>(cols), p[k]));
  return arr;
}

}  // namespace

std::string path_arg(const py::object& path, const std::string& what) {
  const py::object fspath = py::module_::import("os").attr("fspath");
  py::object s;
  try {
    s = fspath(path);
  } catch (const py::error_already_set&) {
    throw InputTypeError(fmt::format("{}: expected a path (str or os.PathLike), got {}", what, type_name(path)));
  }
  if (!py::isinstance<py::str>(s)) throw InputTypeError(fmt::format("{}: expected a text path, got bytes", what));
  const std::string text = s.cast<std::string>();
  if (text.empty()) throw InputError(fmt::format("{}: the path is empty", what));
  if (text.find('\0') != std::string::npos)
    throw InputError(fmt::format("{}: the path holds a NUL character at byte {}; a file name cannot", what,
                                 text.find('\0')));
  return text;
}

std::vector<Eigen::Vector3d> readings_from_array(const py::handle& a, const std::string& what) {
  const auto arr = rows_array(a, 3, what, "gpm.read_samples(path)");
  std::vector<Eigen::Vector3d> out(static_cast<size_t>(arr.shape(0)));
  const double* p = arr.data();
  for (size_t j = 0; j < out.size(); ++j) out[j] = {p[3 * j], p[3 * j + 1], p[3 * j + 2]};
  return out;
}

std::vector<Eigen::Vector2d> points_from_array(const py::handle& a, const std::string& what) {
  const auto arr = rows_array(a, 2, what, "[[216.5, 250.0]]");
  std::vector<Eigen::Vector2d> out(static_cast<size_t>(arr.shape(0)));
  const double* p = arr.data();
  for (size_t j = 0; j < out.size(); ++j) out[j] = {p[2 * j], p[2 * j + 1]};
  return out;
}

py::array_t<double> view_rows(const double* first, size_t n, size_t cols, size_t stride, py::handle base,
                              bool writeable) {
  static const double empty[3] = {0.0, 0.0, 0.0};
  if (n == 0) first = empty;  // a null pointer would make NumPy allocate
  const std::vector<py::ssize_t> shape{static_cast<py::ssize_t>(n), static_cast<py::ssize_t>(cols)};
  const std::vector<py::ssize_t> strides{static_cast<py::ssize_t>(stride), static_cast<py::ssize_t>(sizeof(double))};
  py::array_t<double> a(shape, strides, first, base);
  if (!writeable) py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

py::array_t<double> matrix_array(const Eigen::MatrixXd& m) {
  py::array_t<double> a({static_cast<py::ssize_t>(m.rows()), static_cast<py::ssize_t>(m.cols())});
  auto v = a.mutable_unchecked<2>();
  for (Eigen::Index r = 0; r < m.rows(); ++r)
    for (Eigen::Index c = 0; c < m.cols(); ++c) v(r, c) = m(r, c);
  return a;
}

}  // namespace gpm::python
