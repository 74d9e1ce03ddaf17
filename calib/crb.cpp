#include "calib/crb.hpp"

#include <cmath>
#include <limits>

#include <Eigen/Cholesky>

#include "calib/identifiability.hpp"

namespace gpm::calib {

Eigen::MatrixXd fisher_information(const Geometry& truth, const FreeMask& free,
                                   const std::vector<Eigen::Vector3d>& theta_m, double sigma) {
  const Eigen::MatrixXd J_all = ml_jacobian(theta_m, truth);
  std::vector<Eigen::Index> idx;
  for (int i = 0; i < kNumParams; ++i)
    if (free.test(static_cast<size_t>(i))) idx.push_back(i);
  Eigen::MatrixXd J(J_all.rows(), static_cast<Eigen::Index>(idx.size()));
  for (size_t k = 0; k < idx.size(); ++k) J.col(static_cast<Eigen::Index>(k)) = J_all.col(idx[k]);
  return J.transpose() * J / (sigma * sigma);
}

Eigen::MatrixXd cramer_rao_bound(const Geometry& truth, const FreeMask& free,
                                 const std::vector<Eigen::Vector3d>& theta_m, double sigma) {
  const Eigen::MatrixXd F = fisher_information(truth, free, theta_m, sigma);
  // Invert in the column-scaled metric for accuracy (F spans mm and rad).
  const Eigen::VectorXd d = F.diagonal().cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd Fs = d.asDiagonal() * F * d.asDiagonal();
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(F.rows(), F.cols());
  return d.asDiagonal() * Fs.ldlt().solve(I) * d.asDiagonal();
}

std::array<double, kNumParams> crb_sigma(const Geometry& truth, const FreeMask& free,
                                         const std::vector<Eigen::Vector3d>& theta_m, double sigma) {
  const Eigen::MatrixXd C = cramer_rao_bound(truth, free, theta_m, sigma);
  std::array<double, kNumParams> out;
  out.fill(std::numeric_limits<double>::quiet_NaN());
  Eigen::Index k = 0;
  for (int i = 0; i < kNumParams; ++i)
    if (free.test(static_cast<size_t>(i))) out[static_cast<size_t>(i)] = std::sqrt(C(k, k)), ++k;
  return out;
}

}  // namespace gpm::calib
