// A number as a report's table cell shows it: "-" for a number not measured.
#pragma once

#include <cmath>
#include <string>

#include <fmt/format.h>

namespace gpm::report {

// v formatted by f (an fmt format, e.g. "{:.2f}"), or "-" when v is not finite.
inline std::string table_cell(double v, const char* f) {
  return std::isfinite(v) ? fmt::format(fmt::runtime(f), v) : "-";
}

}  // namespace gpm::report
