// Conversions between the library's types and Python objects for the gpm
// module: geometry dicts, parameter lists, and NumPy arrays that view C++
// memory without copying (the owner is kept alive as the array's base).
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "models/parameters.hpp"
#include "models/robot.hpp"

namespace gpm::python {

namespace py = pybind11;

// {"xa1": ..., ..., "dth3": ...}: all 15 parameters in docs/FORMATS.md order.
py::dict geometry_dict(const Geometry& g);

// The 15 values of a dict; keys not in it keep base's values. Throws
// InputError naming `what` and the nearest valid name for an unknown key.
Geometry geometry_from_dict(const py::dict& d, const Geometry& base, const std::string& what);

// A parameter set from a list of names or one comma-separated string; `what`
// names the argument in errors ("fix[2]: unknown parameter ...").
FreeMask param_set(const py::object& names, const std::string& what);

// The gpm.Robot v of the argument `what`; throws InputTypeError naming it for any other type.
Robot robot_arg(const py::handle& v, const std::string& what);

// Names of the set bits of mask, in index order.
py::list param_names(const FreeMask& mask);

// A file path from a str or os.PathLike; throws InputError naming `what` for
// an empty path or one holding a NUL character (the C library would cut it there).
std::string path_arg(const py::object& path, const std::string& what);

// (n, 3) float64 readings from any array-like; throws InputError naming
// `what` unless it has shape (n, 3) (or (3,) for a single row) of finite numbers.
std::vector<Eigen::Vector3d> readings_from_array(const py::handle& a, const std::string& what);

// (n, 2) float64 points from any array-like; throws InputError unless (n, 2) of finite numbers.
std::vector<Eigen::Vector2d> points_from_array(const py::handle& a, const std::string& what);

// An (n, cols) float64 array viewing vectors of fixed size in place (rows
// `stride` bytes apart, starting at first), owned by base: no copy. Read-only
// unless writeable (views into result objects must not change them).
py::array_t<double> view_rows(const double* first, size_t n, size_t cols, size_t stride, py::handle base,
                              bool writeable = false);

// A (rows, cols) float64 copy of an Eigen matrix (row-major in Python).
py::array_t<double> matrix_array(const Eigen::MatrixXd& m);

}  // namespace gpm::python
