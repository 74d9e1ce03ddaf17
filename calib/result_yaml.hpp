// Calibration result file (YAML, docs/FORMATS.md file contracts): `geometry:` with
// all 15 keys, `std:` with the 1-sigma of each estimated key, `fixed:` list,
// `diagnostics:` (cost, iterations, evaluations, rank, condition_number,
// kmrmse_mm when known, seconds, method, cost_function, converged,
// rank_deficient, notes). Numbers are written exactly (gpm::format_exact) and
// the file atomically; a loaded result can serve as a robot model.
#pragma once

#include <string>

#include "calib/problem.hpp"
#include "models/robot.hpp"

namespace gpm::calib {

// YAML text of a result; robot_name labels it.
std::string result_to_yaml(const Result& r, const std::string& robot_name);

// Writes the result atomically (nothing is left behind on failure).
void save_result(const Result& r, const std::string& robot_name, const std::string& path);

// Parses result YAML text: geometry, free (from `fixed:`), sigma (NaN when
// absent) and the diagnostics present; throws InputError naming file and key.
Result parse_result(const std::string& text, const std::string& file);

// Loads a result file (see parse_result).
Result load_result(const std::string& path);

// The robot `base` (home, branches, limits) with a calibrated geometry;
// throws gpm::Error (the run worked, its result is not a robot: exit 1) when
// a link length is not positive or home is out of reach (issue 36.5).
Robot usable_robot(const Robot& base, const Geometry& calibrated);

// The robot `base` (home, branches, limits) with the calibrated geometry of
// the result file at path: a controller model after calibration.
Robot robot_from_result(const std::string& path, const Robot& base);

}  // namespace gpm::calib
