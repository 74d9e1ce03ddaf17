#include "calib/excitation/candidates.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "models/errors.hpp"
#include "models/kinematics.hpp"

namespace gpm::calib::excitation {

Robot guarded_robot(const Robot& robot, const Guard& guard) {
  Robot r = robot;
  r.limits.reach_margin += guard.reach_mm;
  r.limits.min_transmission += guard.transmission;
  r.limits.min_direct += guard.direct;
  return r;
}

std::vector<Eigen::Vector2d> reachable_grid(const Robot& robot, double step_mm, const Guard& guard) {
  if (!(step_mm > 0.0) || !std::isfinite(step_mm))
    throw InputError(fmt::format("grid step must be a positive number of mm, got {}", step_mm));
  const Robot strict = guarded_robot(robot, guard);
  const Geometry& g = robot.geometry;
  // Bounding box of the intersection of the discs |A_i O| <= la_i + lb_i.
  double x0 = -1e300, x1 = 1e300, y0 = -1e300, y1 = 1e300;
  for (int i = 0; i < kNumChains; ++i) {
    const double R = g.la_(i) + g.lb_(i);
    x0 = std::max(x0, g.A(i).x() - R), x1 = std::min(x1, g.A(i).x() + R);
    y0 = std::max(y0, g.A(i).y() - R), y1 = std::min(y1, g.A(i).y() + R);
  }
  std::vector<Eigen::Vector2d> out;
  if (x0 <= x1 && y0 <= y1) {
    const Eigen::Vector2d h = robot.home;
    const long i0 = static_cast<long>(std::ceil((x0 - h.x()) / step_mm));
    const long i1 = static_cast<long>(std::floor((x1 - h.x()) / step_mm));
    const long j0 = static_cast<long>(std::ceil((y0 - h.y()) / step_mm));
    const long j1 = static_cast<long>(std::floor((y1 - h.y()) / step_mm));
    if ((i1 - i0 + 1) * (j1 - j0 + 1) > 4'000'000)
      throw InputError(fmt::format("grid step {} mm is too fine (more than 4 million grid points)", step_mm));
    for (long j = j0; j <= j1; ++j)
      for (long i = i0; i <= i1; ++i) {
        const Eigen::Vector2d p = h + step_mm * Eigen::Vector2d(static_cast<double>(i), static_cast<double>(j));
        if (check_reach(strict, p).ok) out.push_back(p);
      }
  }
  if (out.empty())
    throw InputError(fmt::format("no grid point of step {} mm is reachable with the margins", step_mm));
  return out;
}

}  // namespace gpm::calib::excitation
