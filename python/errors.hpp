// The gpm module's errors in Python's words: the library's InputError
// messages name command-line flags (`--fix`, `pass --allow-rank-deficient`);
// Python shows the keyword arguments instead (`fix`, `pass
// allow_rank_deficient=True`). Arguments are checked here too: a value of the
// wrong type raises gpm.InputTypeError (a gpm.InputError and a TypeError), a
// value out of range gpm.InputError (a ValueError), each naming the keyword
// and what would be valid.
#pragma once

#include <string>
#include <string_view>

#include <pybind11/pybind11.h>

#include "models/bounds.hpp"
#include "models/errors.hpp"

namespace gpm::python {

// An argument of the wrong type: raised in Python as gpm.InputTypeError.
class InputTypeError : public InputError {
 public:
  explicit InputTypeError(const std::string& what) : InputError(what) {}
};

// message with every command-line flag of the library's messages replaced by
// its Python keyword ("--fix xa1,ya1" -> fix=["xa1", "ya1"], "--model" ->
// robot, a boolean flag -> name=True); a flag of a quoted command ("gpm
// design --count 12") and a flag Python has no keyword for are kept.
std::string python_words(std::string_view message);

// Registers gpm.Error, gpm.InputError, gpm.InputTypeError and gpm.SimError
// and the translator that raises them with the message in Python's words.
void register_errors(pybind11::module_& m);

// The whole number v of the argument `name` within b: InputTypeError unless v
// is an int (or a float with a whole value), InputError naming the valid
// range when out of it (an int of any size: no overflow).
long long whole_arg(const pybind11::handle& v, std::string_view name, const Bound& b);

// The number v of the argument `name` within b: InputTypeError unless v is a
// real number, InputError naming the valid range when out of it.
double number_arg(const pybind11::handle& v, std::string_view name, const Bound& b);

// The str v of the argument `name`; InputTypeError naming `valid` (e.g. "one
// of j1, j2, j3, ml") for any other type.
std::string text_arg(const pybind11::handle& v, std::string_view name, std::string_view valid);

// The bool v (True, False or a NumPy bool) of the argument `name`; InputTypeError otherwise.
bool flag_arg(const pybind11::handle& v, std::string_view name);

// The Python type name of v, for messages ("str", "numpy.ndarray").
std::string type_name(const pybind11::handle& v);

}  // namespace gpm::python
