#include "calib/projected_error.hpp"

#include <Eigen/Dense>
#include <fmt/format.h>

#include "models/errors.hpp"
#include "models/kinematics.hpp"

namespace gpm::calib {
namespace {

void check_lengths(const std::vector<Eigen::Vector2d>& desired, const std::vector<Eigen::Vector3d>& theta_m) {
  if (desired.size() != theta_m.size() || desired.empty()) {
    throw InputError(fmt::format("projected error: {} desired points but {} readings (need the same, "
                                 "at least one)", desired.size(), theta_m.size()));
  }
}

// d theta_a at zero offsets: theta_m - theta_a_hat, wrapped (eq. 2-4).
Eigen::Vector3d raw_error(const Robot& model, const Eigen::Vector2d& p, const Eigen::Vector3d& theta_m) {
  const JointAngles q = inverse_kinematics(model.geometry, p, model.branch);
  Eigen::Vector3d d;
  for (int i = 0; i < 3; ++i) d[i] = wrap_pi(theta_m[i] - q.theta_a[i]);
  return d;
}

}  // namespace

Eigen::Matrix3d infeasible_projection(const Robot& model, const Eigen::Vector2d& p) {
  const JointAngles q = inverse_kinematics(model.geometry, p, model.branch);
  const Matrix32d J = active_jacobian(model.geometry, q);
  return Eigen::Matrix3d::Identity() - J * (J.transpose() * J).inverse() * J.transpose();  // eq. 15
}

double projected_error(const Robot& model, const Eigen::Vector3d& dth,
                       const std::vector<Eigen::Vector2d>& desired,
                       const std::vector<Eigen::Vector3d>& theta_m) {
  check_lengths(desired, theta_m);
  double E = 0.0;
  for (size_t j = 0; j < desired.size(); ++j) {
    const Eigen::Vector3d d_theta_a = raw_error(model, desired[j], theta_m[j]) + dth;  // eq. 3
    const Eigen::Vector3d d_theta_e = infeasible_projection(model, desired[j]) * d_theta_a;  // eq. 17
    E += d_theta_e.squaredNorm();
  }
  return E / static_cast<double>(desired.size());  // eq. 19
}

Eigen::Vector3d minimise_projected_error(const Robot& model, const std::vector<Eigen::Vector2d>& desired,
                                         const std::vector<Eigen::Vector3d>& theta_m) {
  check_lengths(desired, theta_m);
  // P symmetric idempotent (eq. 16): normal equations (sum P_j) dth = -sum P_j c_j.
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (size_t j = 0; j < desired.size(); ++j) {
    const Eigen::Matrix3d P = infeasible_projection(model, desired[j]);
    A += P;
    b -= P * raw_error(model, desired[j], theta_m[j]);
  }
  return A.ldlt().solve(b);
}

}  // namespace gpm::calib
