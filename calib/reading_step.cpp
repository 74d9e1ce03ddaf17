// The encoders' resolution from their readings (calib/reading_step.hpp).
#include "calib/reading_step.hpp"

#include <algorithm>
#include <cmath>

namespace gpm::calib {
namespace {

// The step of one joint's readings, or nullopt (reading_step).
std::optional<double> joint_step(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  if (v.size() < 100) return std::nullopt;
  std::vector<double> gaps;
  for (std::size_t j = 1; j < v.size(); ++j) gaps.push_back(v[j] - v[j - 1]);
  const double q = *std::min_element(gaps.begin(), gaps.end());
  if (!(q > 0.0)) return std::nullopt;
  const auto whole = std::count_if(gaps.begin(), gaps.end(), [q](double g) {
    const double k = g / q;
    return std::abs(k - std::round(k)) <= 0.02;
  });
  if (static_cast<double>(whole) < 0.99 * static_cast<double>(gaps.size())) return std::nullopt;
  return q;
}

}  // namespace

std::optional<double> reading_step(const std::vector<Eigen::Vector3d>& theta_m) {
  double step = 0.0;
  for (int i = 0; i < 3; ++i) {
    std::vector<double> v;
    v.reserve(theta_m.size());
    for (const Eigen::Vector3d& m : theta_m) v.push_back(m[i]);
    const std::optional<double> q = joint_step(std::move(v));
    if (!q) return std::nullopt;
    step = std::max(step, *q);
  }
  return step;
}

}  // namespace gpm::calib
