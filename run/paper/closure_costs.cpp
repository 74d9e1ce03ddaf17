#include "run/paper/closure_costs.hpp"

#include <limits>

#include "models/kinematics.hpp"

namespace gpm::paper {

ClosureCosts closure_costs(const Geometry& g, const std::vector<Eigen::Vector3d>& theta_m) {
  ClosureCosts c;
  for (const Eigen::Vector3d& m : theta_m) {
    const Eigen::Vector3d theta_a = active_from_readings(g, m);
    const auto fk = forward_kinematics(g, theta_a);
    if (!fk) {
      c.j1 = c.j23 = std::numeric_limits<double>::infinity();
      return c;
    }
    const auto b = elbows(g, theta_a);
    for (int i = 0; i < kNumChains; ++i) {
      const double dist = (fk->p - b[static_cast<size_t>(i)]).norm();
      const double lb = g.lb_(i);
      c.j1 += (dist - lb) * (dist - lb);
      const double power = dist * dist - lb * lb;
      c.j23 += power * power;
    }
  }
  return c;
}

}  // namespace gpm::paper
