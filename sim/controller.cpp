#include "sim/controller.hpp"

#include "models/kinematics.hpp"

namespace gpm::sim {

JointCommand command_for(const Robot& controller, const PathPoint& target) {
  return command_at(controller, inverse_kinematics(controller.geometry, target.p, controller.branch), target);
}

JointCommand command_at(const Robot& controller, const JointAngles& q, const PathPoint& target) {
  const Geometry& g = controller.geometry;
  JointCommand c;
  const Eigen::Vector3d m = readings_from_active(g, q.theta_a);
  for (int i = 0; i < 3; ++i) c.position[i] = wrap_2pi(m[i]);
  c.velocity = active_jacobian(g, q) * target.v;
  return c;
}

}  // namespace gpm::sim
