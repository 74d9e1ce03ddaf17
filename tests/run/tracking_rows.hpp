// Helper of the tests of run/ that judge a sampled path against its plan
// (test_sampling_design.cpp, test_offsets_first.cpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "sim/sampling.hpp"

namespace gpm::test {

// Largest distance of the twin's true end-effector from the plan over rows
// logged up to until_s (mm).
inline double worst_row_deviation_mm(const std::vector<sim::LogRow>& rows, double until_s = INFINITY) {
  double worst = 0.0;
  for (const sim::LogRow& row : rows)
    if (row.t <= until_s) worst = std::max(worst, (row.actual - row.desired).norm());
  return worst;
}

}  // namespace gpm::test
