// Checks of encoder samples against a calibration problem before solving
// (docs/ARCHITECTURE.md: bad input is refused with one line naming where).
#pragma once

#include <string>
#include <vector>

#include "calib/problem.hpp"

namespace gpm::calib {

// Relative slack (of lb_i + lb_j) before two passive circles count as not
// meeting at the start geometry: start errors of 0.03 rad in the offsets move
// an elbow by ~7 mm, well inside; a wrong reading moves it by far more.
inline constexpr double kCircleGapTolerance = 0.03;

// Throws InputError when there are fewer samples than free parameters, a
// reading is not finite, or a sample's three passive circles do not meet at
// the start geometry (pairwise: |B_i - B_j| outside [|lb_i - lb_j|, lb_i + lb_j]
// by more than kCircleGapTolerance, or collinear elbows). labels[j], when given, names sample j in the message
// (e.g. "samples.csv:7 (sample 5)"); otherwise "sample j".
void check_samples(const Problem& problem, const std::vector<std::string>& labels = {});

}  // namespace gpm::calib
