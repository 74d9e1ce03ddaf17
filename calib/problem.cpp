#include "calib/problem.hpp"

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

}  // namespace gpm::calib
