#include "calib/excitation/fisher.hpp"

#include <cmath>
#include <limits>

#include <Eigen/SVD>
#include <fmt/format.h>

#include "calib/identifiability.hpp"
#include "models/errors.hpp"
#include "models/kinematics.hpp"

namespace gpm::calib::excitation {

Eigen::MatrixXd information_rows(const Robot& robot, const FreeMask& free,
                                 const std::vector<Eigen::Vector2d>& poses) {
  std::vector<Eigen::Vector3d> theta_m;
  theta_m.reserve(poses.size());
  for (const Eigen::Vector2d& p : poses) {
    const JointAngles q = inverse_kinematics(robot.geometry, p, robot.branch);
    theta_m.push_back(readings_from_active(robot.geometry, q.theta_a));
  }
  // Rows of the ML residual's Jacobian at the noiseless readings (calib/crb.hpp).
  const Eigen::MatrixXd J_all = ml_jacobian(theta_m, robot.geometry);
  Eigen::MatrixXd rows(J_all.rows(), static_cast<Eigen::Index>(free.count()));
  Eigen::Index k = 0;
  for (int i = 0; i < kNumParams; ++i)
    if (free.test(static_cast<size_t>(i))) rows.col(k++) = J_all.col(i);
  for (Eigen::Index j = 0; j < rows.rows(); ++j)
    if (!rows.row(j).allFinite())
      throw InputError(fmt::format("pose ({}, {}): degenerate (collinear elbows), no information",
                                   poses[static_cast<size_t>(j)].x(), poses[static_cast<size_t>(j)].y()));
  return rows;
}

Eigen::MatrixXd fisher_information(const Eigen::MatrixXd& rows, double sigma) {
  if (!(sigma > 0.0)) throw InputError(fmt::format("noise sigma must be positive, got {}", sigma));
  return rows.transpose() * rows / (sigma * sigma);
}

Eigen::VectorXd parameter_scale(const Geometry& g, const FreeMask& free) {
  Eigen::VectorXd s(static_cast<Eigen::Index>(free.count()));
  Eigen::Index k = 0;
  for (int i = 0; i < kNumParams; ++i) {
    if (!free.test(static_cast<size_t>(i))) continue;
    s[k++] = is_offset(i) ? g.la_(i - kDth1) : 1.0;
  }
  return s;
}

Bounds bounds_from_rows(const Eigen::MatrixXd& rows, const Geometry& g, const FreeMask& free,
                        double sigma) {
  Bounds b;
  for (int i = 0; i < kNumParams; ++i)
    if (free.test(static_cast<size_t>(i))) b.free_index.push_back(i);
  const Eigen::VectorXd s = parameter_scale(g, free);
  const Eigen::Index p = s.size();
  // Work in scaled units theta_s = s .* theta (all mm): rows_s = rows / s, so
  // F_s = D^-1 F D^-1 with D = diag(s), C_s = D C D, scaled sigma_k = s_k sigma_k.
  Eigen::MatrixXd rows_s = rows;
  for (Eigen::Index k = 0; k < p; ++k) rows_s.col(k) /= s[k];
  // Through the SVD of the scaled rows rather than F itself: singular values
  // are accurate to eps * largest, so a layout as poor as a line (condition
  // number ~1e10, docs/EQUATIONS.md) still gets finite bounds. With rows_s = U S V',
  // F_s = V S^2 V' / sigma^2 and C_s = sigma^2 V S^-2 V'.
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(rows_s, Eigen::ComputeThinV);
  const Eigen::VectorXd sv = svd.singularValues();  // descending
  const double inf = std::numeric_limits<double>::infinity();
  b.sigma = Eigen::VectorXd::Constant(p, inf);
  b.scaled = Eigen::VectorXd::Constant(p, inf);
  b.worst_mm = inf;
  b.mean_mm = inf;
  b.log_det = -inf;
  if (!(sigma > 0.0)) throw InputError(fmt::format("noise sigma must be positive, got {}", sigma));
  // Rank test as calib/identifiability.hpp (exact gauge directions sit at ~1e-15).
  if (p == 0 || rows_s.rows() < p || !(sv[p - 1] > kRankTolerance * sv[0])) return b;
  // log det F = 2 sum log sv + 2 sum log s - 2 p log sigma. Scalar logs: GCC 12
  // warns falsely inside Eigen's AVX-512 vectorised log (GCC PR 105593).
  double log_sum = 0.0;
  for (Eigen::Index k = 0; k < p; ++k) log_sum += std::log(sv[k]) + std::log(s[k]);
  b.log_det = 2.0 * log_sum - 2.0 * static_cast<double>(p) * std::log(sigma);
  const Eigen::MatrixXd W = svd.matrixV() * sv.cwiseInverse().asDiagonal();
  b.scaled = sigma * W.rowwise().norm();
  b.sigma = b.scaled.cwiseQuotient(s);
  Eigen::Index worst = 0;
  b.worst_mm = b.scaled.maxCoeff(&worst);
  b.worst_param = b.free_index[static_cast<size_t>(worst)];
  b.mean_mm = b.scaled.mean();
  return b;
}

Bounds pose_bounds(const Robot& robot, const FreeMask& free,
                   const std::vector<Eigen::Vector2d>& poses, double sigma) {
  return bounds_from_rows(information_rows(robot, free, poses), robot.geometry, free, sigma);
}

}  // namespace gpm::calib::excitation
