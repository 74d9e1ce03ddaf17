// Regular pose layouts (models/pose_layouts.hpp).
#include "models/pose_layouts.hpp"

#include <cmath>
#include <numbers>

namespace gpm {

std::vector<Eigen::Vector2d> circle_points(const Eigen::Vector2d& centre, double radius, int count) {
  std::vector<Eigen::Vector2d> out;
  for (int k = 0; k < count; ++k) {
    const double a = 2.0 * std::numbers::pi * k / count;
    out.push_back(centre + radius * Eigen::Vector2d(std::cos(a), std::sin(a)));
  }
  return out;
}

std::vector<Eigen::Vector2d> line_points(const Eigen::Vector2d& from, const Eigen::Vector2d& to, int count) {
  std::vector<Eigen::Vector2d> out;
  for (int k = 0; k < count; ++k) {
    const double u = count > 1 ? static_cast<double>(k) / (count - 1) : 0.0;
    out.push_back(from + u * (to - from));
  }
  return out;
}

}  // namespace gpm
