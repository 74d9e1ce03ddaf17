// Regular layouts of end-effector poses (mm): evenly spaced on a circle or a
// line. The one home of these layouts for sampling plans (sim/), excitation
// comparisons (calib/excitation/) and the section-3 offset check (hw/).
#pragma once

#include <vector>

#include <Eigen/Core>

namespace gpm {

// count points evenly spaced on a circle, the first at centre + (radius, 0),
// counter-clockwise.
std::vector<Eigen::Vector2d> circle_points(const Eigen::Vector2d& centre, double radius, int count);

// count points evenly spaced from `from` to `to`, both ends included
// (count >= 2; one point, `from`, for count 1).
std::vector<Eigen::Vector2d> line_points(const Eigen::Vector2d& from, const Eigen::Vector2d& to, int count);

}  // namespace gpm
