// Kinematics of the 3-RRR planar manipulator (paper eq. 5-11, 29-35; docs/EQUATIONS.md).
// Free functions of a constant model: f(geometry, ...). Millimetres, radians.
//
// Chain i: base joint A_i, active link la_i at angle theta_a_i to the elbow
// B_i = A_i + la_i (cos theta_a_i, sin theta_a_i) (eq. 30), passive link lb_i
// at angle theta_b_i to the end-effector O = B_i + lb_i (cos theta_b_i,
// sin theta_b_i) (eq. 29). Encoders read theta_m = theta_a - dth (eq. 35).
#pragma once

#include <array>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "models/errors.hpp"
#include "models/robot.hpp"

namespace gpm {

using Matrix32d = Eigen::Matrix<double, 3, 2>;

// A target that some chain cannot reach. Carries the chain and the shortfall.
class ReachError : public InputError {
 public:
  ReachError(const std::string& what, int chain, double shortfall_mm)
      : InputError(what), chain(chain), shortfall_mm(shortfall_mm) {}
  int chain;            // 0-based chain index
  double shortfall_mm;  // how far outside the chain's annulus the target is
};

// Joint angles of one chain.
struct ChainAngles {
  double theta_a = 0.0;
  double theta_b = 0.0;
};

// Joint angles of the whole mechanism.
struct JointAngles {
  Eigen::Vector3d theta_a = Eigen::Vector3d::Zero();
  Eigen::Vector3d theta_b = Eigen::Vector3d::Zero();
};

// Inverse kinematics of chain i (eq. 31 solved for theta_a): the elbow angle
// alpha = acos((la^2 + d^2 - lb^2) / (2 la d)) at A_i, theta_a = phi + branch
// * alpha with phi the direction of A_i -> p. nullopt when p is outside the
// annulus |la - lb| <= |A_i p| <= la + lb. theta_a in [0, 2 pi), theta_b in
// (-pi, pi] (eq. 34).
std::optional<ChainAngles> try_chain_ik(const Geometry& g, int i, const Eigen::Vector2d& p,
                                        int branch);

// As try_chain_ik, but throws ReachError naming the chain and by how much the
// target is out of reach.
ChainAngles chain_ik(const Geometry& g, int i, const Eigen::Vector2d& p, int branch);

// Inverse kinematics of all three chains on the given branches; throws ReachError.
JointAngles inverse_kinematics(const Geometry& g, const Eigen::Vector2d& p,
                               const Branches& branch = {1, 1, 1});

// As inverse_kinematics, but nullopt when some chain cannot reach p.
std::optional<JointAngles> try_inverse_kinematics(const Geometry& g, const Eigen::Vector2d& p,
                                                  const Branches& branch = {1, 1, 1});

// Elbow points B_i = A_i + la_i (cos theta_a_i, sin theta_a_i) (eq. 30).
std::array<Eigen::Vector2d, 3> elbows(const Geometry& g, const Eigen::Vector3d& theta_a);

// Result of forward kinematics from the three active angles.
struct ForwardResult {
  Eigen::Vector2d p = Eigen::Vector2d::Zero();  // end-effector O (mm)
  Eigen::Vector3d theta_b = Eigen::Vector3d::Zero();
  // Power of O with respect to each passive circle, |O - B_i|^2 - lb_i^2
  // (mm^2): equal for all three chains at the radical centre (docs/EQUATIONS.md), zero
  // when the readings close the loops exactly.
  double power = 0.0;
};

// Forward kinematics from three active angles: the radical centre of the three
// passive circles (eq. 32-33 with squares restored and solved relative to B1;
// gpm::radical_centre of models/closure.hpp) and the passive angles by atan2
// (eq. 34). nullopt when the elbows are collinear (no unique radical centre).
std::optional<ForwardResult> forward_kinematics(const Geometry& g, const Eigen::Vector3d& theta_a);

// The two intersections of circles (c1, r1) and (c2, r2); nullopt if they do
// not meet. Element 0 lies left of c1 -> c2 (positive cross product).
std::optional<std::array<Eigen::Vector2d, 2>> circle_intersections(const Eigen::Vector2d& c1,
                                                                   double r1,
                                                                   const Eigen::Vector2d& c2,
                                                                   double r2);

// Assembly mode of the chain pair (i, j) at end-effector p: +1 when p lies
// left of B_i -> B_j, -1 otherwise.
int assembly_mode(const Geometry& g, const Eigen::Vector3d& theta_a, const Eigen::Vector2d& p,
                  int i, int j);

// Forward kinematics from chains i and j only: intersection of their passive
// circles in the given assembly mode (for cross checks and a redundant-sensor
// consistency test). nullopt if the circles do not meet.
std::optional<Eigen::Vector2d> forward_kinematics_two(const Geometry& g,
                                                      const Eigen::Vector3d& theta_a, int i,
                                                      int j, int mode);

// Jacobian of the active angles with respect to the end-effector (eq. 11,
// with la_i for l): d theta_a_i / d(x, y) = -(cos theta_b_i, sin theta_b_i) /
// (la_i sin(theta_a_i - theta_b_i)). Units rad/mm.
Matrix32d active_jacobian(const Geometry& g, const JointAngles& q);

// Distance to both singularity types and the conditioning of eq. 11.
struct Conditioning {
  // Type 1 (serial): |sin(theta_a_i - theta_b_i)| per chain; 0 when active and
  // passive links are aligned.
  Eigen::Vector3d transmission = Eigen::Vector3d::Zero();
  double min_transmission = 0.0;
  // Type 2 (parallel): smallest singular value of the 3x2 matrix of passive
  // link directions, divided by sqrt(3/2) (1 for directions 120 deg apart, 0
  // when all three are parallel).
  double direct = 0.0;
  // Condition number sigma_max / sigma_min of the active Jacobian (eq. 11).
  double jacobian_condition = 0.0;
};

// Conditioning of the mechanism at joint angles q (every measure NaN when an
// angle is not finite).
Conditioning conditioning(const Geometry& g, const JointAngles& q);

// Reachability of a target with the robot's margins.
struct Reach {
  bool ok = false;
  std::string reason;  // empty when ok; otherwise what is violated and by how much
  JointAngles q;       // valid when the IK succeeded
  Conditioning cond;   // valid when the IK succeeded
};

// Whether p is reachable on the robot's branches while keeping reach_margin
// from each annulus edge and the singularity margins of robot.limits.
Reach check_reach(const Robot& robot, const Eigen::Vector2d& p);

// Encoder readings of active angles: theta_m = theta_a - dth (eq. 35).
Eigen::Vector3d readings_from_active(const Geometry& g, const Eigen::Vector3d& theta_a);

// Active angles from readings: theta_a = theta_m + dth (eq. 35).
Eigen::Vector3d active_from_readings(const Geometry& g, const Eigen::Vector3d& theta_m);

// Wraps an angle to (-pi, pi].
double wrap_pi(double a);

// Wraps an angle to [0, 2 pi) (IK reports active angles so: home is about
// 1.111, 3.111, 4.825 rad).
double wrap_2pi(double a);

}  // namespace gpm
