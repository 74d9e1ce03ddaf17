// Numbers as the run's JSON and Markdown outputs write them: JSON has no NaN
// or infinity (null instead), a table cell shows "-" for a number not measured.
#pragma once

#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "report/table_cell.hpp"

namespace gpm::scenario {

// v, or null when v is not finite.
inline nlohmann::json json_finite(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

// v formatted by f (an fmt format, e.g. "{:.2f}"), or "-" when v is not finite (report/table_cell.hpp).
using report::table_cell;

}  // namespace gpm::scenario
