#include "sim/controller.hpp"

#include "models/kinematics.hpp"

namespace gpm::sim {

JointCommand command_for(const Robot& controller, const PathPoint& target) {
  const Geometry& g = controller.geometry;
  const JointAngles q = inverse_kinematics(g, target.p, controller.branch);
  JointCommand c;
  const Eigen::Vector3d m = readings_from_active(g, q.theta_a);
  for (int i = 0; i < 3; ++i) c.position[i] = wrap_2pi(m[i]);
  c.velocity = active_jacobian(g, q) * target.v;
  return c;
}

}  // namespace gpm::sim
