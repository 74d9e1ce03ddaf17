#include "calib/problem.hpp"

#include <fmt/format.h>

#include "models/errors.hpp"

namespace gpm::calib {

std::optional<Cost> parse_cost(std::string_view name) {
  if (name == "j1") return Cost::kJ1;
  if (name == "j2") return Cost::kJ2;
  if (name == "j3") return Cost::kJ3;
  if (name == "ml") return Cost::kML;
  return std::nullopt;
}

std::string_view cost_name(Cost c) {
  switch (c) {
    case Cost::kJ1: return "j1";
    case Cost::kJ2: return "j2";
    case Cost::kJ3: return "j3";
    case Cost::kML: return "ml";
  }
  return "?";
}

Method parse_method(std::string_view name, std::string_view where) {
  if (name == "lm") return Method::kLM;
  if (name == "ga") return Method::kGA;
  if (name == "pso") return Method::kPSO;
  if (name == "de") return Method::kDE;
  if (name == "de+lm") return Method::kDELM;
  throw InputError(fmt::format("{}: unknown method '{}' (valid: {})", where, name, kMethodNames));
}

std::string_view method_name(Method m) {
  switch (m) {
    case Method::kLM: return "lm";
    case Method::kGA: return "ga";
    case Method::kPSO: return "pso";
    case Method::kDE: return "de";
    case Method::kDELM: return "de+lm";
  }
  return "?";
}

}  // namespace gpm::calib
