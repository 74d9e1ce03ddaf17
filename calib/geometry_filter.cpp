#include "calib/geometry_filter.hpp"

#include <cmath>
#include <optional>

#include "calib/residuals.hpp"

namespace gpm::calib {
namespace {

// The ML closure residual of theta_m under g (rad, calib/residuals.hpp
// MlResidual); nullopt without a radical centre, a gradient or a finite value.
std::optional<double> ml_residual(const Geometry& g, const Eigen::Vector3d& theta_m) {
  double r = 0.0;
  if (!MlResidual(theta_m)(g.values.data(), &r) || !std::isfinite(r)) return std::nullopt;
  return r;
}

}  // namespace

GeometryFilter::GeometryFilter(const Geometry& controller, const GeometryFilterSettings& settings)
    : geometry_(controller), misfit_variance_(settings.misfit_sigma_rad * settings.misfit_sigma_rad) {
  for (int p = 0; p < kNumParams; ++p)
    if (!settings.held.test(static_cast<std::size_t>(p))) free_.push_back(p);
  const auto n = static_cast<Eigen::Index>(free_.size());
  sigma_ = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index k = 0; k < n; ++k) sigma_(k, k) = std::pow(tolerance_of(settings.prior, free_[k]), 2);
}

void GeometryFilter::update(const Eigen::Vector3d& theta_m) {
  constexpr double kStep = 1e-7;  // mm or rad: forward differences of a residual of ~1e-3
  const std::optional<double> r = ml_residual(geometry_, theta_m);
  if (!r) return;
  const auto n = static_cast<Eigen::Index>(free_.size());
  Eigen::RowVectorXd H(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    Geometry moved = geometry_;
    moved[free_[k]] += kStep;
    const std::optional<double> rk = ml_residual(moved, theta_m);
    if (!rk) return;
    H[k] = (*rk - *r) / kStep;
  }
  const Eigen::VectorXd sigma_Ht = sigma_ * H.transpose();
  const double s = H.dot(sigma_Ht) + misfit_variance_;
  const Eigen::VectorXd K = sigma_Ht / s;
  for (Eigen::Index k = 0; k < n; ++k) geometry_[free_[k]] -= K[k] * *r;
  const Eigen::MatrixXd I_KH = Eigen::MatrixXd::Identity(n, n) - K * H;
  sigma_ = I_KH * sigma_ * I_KH.transpose() + misfit_variance_ * K * K.transpose();
  ++updates_;
}

}  // namespace gpm::calib
