// Samples in which a passive link may be crossing its play (calib/play_crossing.hpp).
#include "calib/play_crossing.hpp"

namespace gpm::calib {

std::vector<std::array<bool, 3>> play_crossing(const std::vector<std::optional<Eigen::Vector3d>>& tension, int samples) {
  std::vector<std::array<bool, 3>> out(tension.size(), {false, false, false});
  if (samples <= 0) return out;
  for (int i = 0; i < 3; ++i) {
    std::optional<bool> positive;  // the sign of the last known force
    std::size_t until = 0;         // the window of the last sign change ends before this sample
    for (std::size_t j = 0; j < tension.size(); ++j) {
      if (tension[j]) {
        const bool now = (*tension[j])[i] > 0.0;
        if (positive && now != *positive) until = j + static_cast<std::size_t>(samples);
        positive = now;
      }
      out[j][static_cast<std::size_t>(i)] = j < until;
    }
  }
  return out;
}

}  // namespace gpm::calib
