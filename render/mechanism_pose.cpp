#include "render/mechanism_pose.hpp"

#include <algorithm>
#include <cmath>

#include "sim/mujoco_util.hpp"

namespace gpm::render {

const sim::LogRow& row_at(const sim::TrajectoryLog& log, double t) {
  // Within a nanosecond counts as at t: a frame time summed otherwise than the
  // log's times (a part logged from 15.545 s) picks the same row.
  const auto it = std::upper_bound(log.rows.begin(), log.rows.end(), t,
                                   [](double v, const sim::LogRow& r) { return v + kSameTime_s < r.t; });
  if (it == log.rows.begin()) return log.rows.front();
  return *(it - 1);
}

JointAngles pose_of(const Robot& actual, const sim::LogRow& row) {
  const Geometry& g = actual.geometry;
  if (const std::optional<JointAngles> reached = try_inverse_kinematics(g, row.actual, actual.branch)) return *reached;
  JointAngles q;
  q.theta_a = active_from_readings(g, row.readings);
  const auto b = elbows(g, q.theta_a);
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d d = row.actual - b[i];
    q.theta_b[i] = std::atan2(d.y(), d.x());
  }
  return q;
}

JointAddresses joint_addresses(const mjModel* m) {
  JointAddresses adr;
  for (int i = 0; i < 3; ++i) {
    const std::string a = "joint_a" + std::to_string(i + 1);
    const std::string b = "joint_b" + std::to_string(i + 1);
    adr.a[i] = m->jnt_qposadr[sim::require_id(m, mjOBJ_JOINT, a.c_str())];
    adr.b[i] = m->jnt_qposadr[sim::require_id(m, mjOBJ_JOINT, b.c_str())];
  }
  return adr;
}

void apply_pose(const mjModel* m, mjData* d, const JointAddresses& adr, const JointAngles& q) {
  for (int i = 0; i < m->nv; ++i) d->qvel[i] = 0.0;
  for (int i = 0; i < 3; ++i) {
    d->qpos[adr.a[i]] = q.theta_a[i];
    d->qpos[adr.b[i]] = q.theta_b[i] - q.theta_a[i];
  }
  mj_kinematics(m, d);
  mj_camlight(m, d);
}

}  // namespace gpm::render
