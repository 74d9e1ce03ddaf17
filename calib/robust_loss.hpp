// Robust losses for the calibration (`gpm calibrate --loss cauchy|huber[:SCALE]`,
// scenario `calibration: {loss: ...}`): Ceres' CauchyLoss and HuberLoss
// applied per sample, so that a few outlier samples (a bad reading, a bump)
// do not drag the parameters.
//
// Ceres minimises 1/2 sum_j rho(s_j), s_j = |r_j|^2 for the residual group
// r_j of sample j (1 row for ML and J1, 2 for J2, 3 for J3). As a plain least
// squares problem this is sum_j |r~_j|^2 / 2 with
//   r~_j = sqrt(rho(s_j) / s_j) r_j                          (r~_j = r_j at s_j = 0)
//   d r~_j / d x = W_j d r_j / d x,
//   W_j = sqrt(rho/s) (I + (s rho'/rho - 1) r_j r_j' / s),
// the exact Jacobian of r~_j, so the Gauss-Newton model, the cost Ceres
// accepts steps on and the covariance (J~' J~)^-1 all belong to the robust
// problem. For samples well inside the scale (s << scale^2), rho(s) = s and
// W_j = I: the inliers count as in the plain fit.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

namespace ceres {
class CostFunction;
class LossFunction;
}  // namespace ceres

namespace gpm::calib {

enum class LossKind { kPlain, kHuber, kCauchy };

// A loss and its scale (in the residual's units: rad for ML; 0 = not given,
// the caller chooses one from the noise).
struct RobustLoss {
  LossKind kind = LossKind::kPlain;
  double scale = 0.0;
  bool active() const { return kind != LossKind::kPlain; }
};

// "plain", "cauchy", "huber", "cauchy:SCALE", "huber:SCALE" -> RobustLoss.
// Throws InputError "<where>: ..." naming the valid forms otherwise (SCALE a
// positive finite number).
RobustLoss parse_loss(std::string_view text, std::string_view where = "--loss");

// Scale in units of the noise sigma for 95 % efficiency under Gaussian
// noise: 2.385 (Cauchy), 1.345 (Huber); 0 for plain.
double default_tuning(LossKind kind);

// The noise 1-sigma of residuals r robustly: 1.4826 x the median of |r|
// (the median absolute deviation of residuals centred on 0, scaled to a
// Gaussian's sigma); 0 for none. r is reordered.
double robust_sigma(std::vector<double> r);

// "plain", "cauchy:0.0001", ... (for reports).
std::string loss_name(const RobustLoss& loss);

// The Ceres loss function of loss (scale must be positive); nullptr for plain.
std::unique_ptr<ceres::LossFunction> make_loss_function(const RobustLoss& loss);

// W_j of the header comment for one residual group r (rows x rows).
Eigen::MatrixXd robust_factor(const ceres::LossFunction& rho, const Eigen::VectorXd& r);

// r~ of the header comment for one residual group.
Eigen::VectorXd robust_residual(const ceres::LossFunction& rho, const Eigen::VectorXd& r);

// Wraps a cost function whose residuals are consecutive groups of `rows`
// (one per sample) into r~ (header comment). Neither pointer is owned.
std::unique_ptr<ceres::CostFunction> make_robust_residual(ceres::CostFunction* inner, int rows,
                                                          const ceres::LossFunction* rho);

}  // namespace gpm::calib
