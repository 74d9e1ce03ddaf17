// Robust losses for the calibration (calib/robust_loss.hpp).
#include "calib/robust_loss.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <ceres/ceres.h>
#include <fmt/format.h>

#include "models/bounds.hpp"
#include "models/errors.hpp"

namespace gpm::calib {
namespace {

// rho(s) / s and rho'(s) of a Ceres loss. Deep inside the scale (rho' within
// 1e-6 of 1) rho(s) / s is taken as (1 + rho') / 2, exact to second order for
// smooth losses: Ceres' Cauchy evaluates log(1 + s/b) without log1p, which
// loses the relative accuracy of rho(s) for s << b.
void rho_of(const ceres::LossFunction& rho, double s, double& ratio, double& slope) {
  double out[3];
  rho.Evaluate(s, out);
  slope = out[1];
  ratio = 1.0 - slope < 1e-6 ? 0.5 * (1.0 + slope) : out[0] / s;
}

class RobustResidual final : public ceres::CostFunction {
 public:
  RobustResidual(ceres::CostFunction* inner, int rows, const ceres::LossFunction* rho)
      : inner_(inner), rows_(rows), rho_(rho) {
    set_num_residuals(inner->num_residuals());
    *mutable_parameter_block_sizes() = inner->parameter_block_sizes();
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    return inner_->Evaluate(parameters, residuals, jacobians) && make_robust(residuals, jacobians);
  }

 private:
  // r~ and W_j J in place; false when any is not finite (a loss that
  // overflows or underflows, issue 36.1): Ceres then takes the point as one
  // where the cost cannot be evaluated instead of stepping on NaN.
  bool make_robust(double* residuals, double** jacobians) const {
    const int n = num_residuals();
    const int groups = n / rows_;
    Eigen::Map<Eigen::VectorXd> r(residuals, n);
    for (int g = 0; g < groups; ++g) {
      const Eigen::VectorXd rj = r.segment(g * rows_, rows_);
      if (jacobians) {
        const Eigen::MatrixXd W = robust_factor(*rho_, rj);
        for (std::size_t b = 0; b < parameter_block_sizes().size(); ++b) {
          if (!jacobians[b]) continue;
          const int cols = parameter_block_sizes()[b];
          Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> J(jacobians[b], n, cols);
          J.middleRows(g * rows_, rows_) = W * J.middleRows(g * rows_, rows_);
        }
      }
      r.segment(g * rows_, rows_) = robust_residual(*rho_, rj);
    }
    if (!r.allFinite()) return false;
    for (std::size_t b = 0; jacobians && b < parameter_block_sizes().size(); ++b) {
      if (!jacobians[b]) continue;
      const Eigen::Map<const Eigen::VectorXd> J(jacobians[b], n * parameter_block_sizes()[b]);
      if (!J.allFinite()) return false;
    }
    return true;
  }

  ceres::CostFunction* inner_;
  int rows_;
  const ceres::LossFunction* rho_;
};

}  // namespace

RobustLoss parse_loss(std::string_view text, std::string_view where) {
  const std::string t(text);
  const std::string valid = "valid: plain, cauchy, huber, or cauchy:SCALE / huber:SCALE with SCALE a positive "
                            "residual size, e.g. huber:1e-4 (rad for the ML cost)";
  const auto colon = t.find(':');
  const std::string name = t.substr(0, colon);
  RobustLoss loss;
  if (name == "plain") loss.kind = LossKind::kPlain;
  else if (name == "cauchy") loss.kind = LossKind::kCauchy;
  else if (name == "huber") loss.kind = LossKind::kHuber;
  else throw InputError(fmt::format("{}: unknown loss '{}' ({})", where, t, valid));
  if (colon != std::string::npos) {
    const std::string num = t.substr(colon + 1);
    std::size_t used = 0;
    double v = 0.0;
    try {
      v = std::stod(num, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (loss.kind == LossKind::kPlain || used == 0 || used != num.size() || !std::isfinite(v) || !(v > 0.0))
      throw InputError(fmt::format("{}: '{}' has no valid scale ({})", where, t, valid));
    // A scale whose square underflows or overflows breaks the loss (issue 36.1).
    loss.scale = check_bound(v, limits::kLossScale, fmt::format("{}: scale of '{}'", where, t), num);
  }
  return loss;
}

double robust_sigma(std::vector<double> r) {
  if (r.empty()) return 0.0;
  for (double& x : r) x = std::abs(x);
  const auto mid = r.begin() + static_cast<std::ptrdiff_t>(r.size() / 2);
  std::nth_element(r.begin(), mid, r.end());
  return 1.4826 * *mid;
}

double default_tuning(LossKind kind) {
  return kind == LossKind::kCauchy ? 2.385 : kind == LossKind::kHuber ? 1.345 : 0.0;
}

std::string loss_name(const RobustLoss& loss) {
  const char* n = loss.kind == LossKind::kCauchy ? "cauchy" : loss.kind == LossKind::kHuber ? "huber" : "plain";
  return loss.active() && loss.scale > 0.0 ? fmt::format("{}:{:.3g}", n, loss.scale) : std::string(n);
}

std::unique_ptr<ceres::LossFunction> make_loss_function(const RobustLoss& loss) {
  if (!loss.active()) return nullptr;
  if (!(loss.scale > 0.0) || !std::isfinite(loss.scale))
    throw InputError(fmt::format("loss {}: the scale must be a positive number, got {}", loss_name(loss), loss.scale));
  if (loss.kind == LossKind::kCauchy) return std::make_unique<ceres::CauchyLoss>(loss.scale);
  return std::make_unique<ceres::HuberLoss>(loss.scale);
}

Eigen::MatrixXd robust_factor(const ceres::LossFunction& rho, const Eigen::VectorXd& r) {
  const Eigen::Index m = r.size();
  const double s = r.squaredNorm();
  if (!(s > 0.0)) return Eigen::MatrixXd::Identity(m, m);  // rho(s) = s near 0 for Ceres' losses
  double ratio = 0.0, slope = 0.0;
  rho_of(rho, s, ratio, slope);
  if (!(ratio > 0.0)) return Eigen::MatrixXd::Identity(m, m);
  return std::sqrt(ratio) * (Eigen::MatrixXd::Identity(m, m) + (slope / ratio - 1.0) * (r * r.transpose()) / s);
}

Eigen::VectorXd robust_residual(const ceres::LossFunction& rho, const Eigen::VectorXd& r) {
  const double s = r.squaredNorm();
  if (!(s > 0.0)) return r;
  double ratio = 0.0, slope = 0.0;
  rho_of(rho, s, ratio, slope);
  return std::sqrt(ratio) * r;
}

std::unique_ptr<ceres::CostFunction> make_robust_residual(ceres::CostFunction* inner, int rows,
                                                          const ceres::LossFunction* rho) {
  return std::make_unique<RobustResidual>(inner, rows, rho);
}

}  // namespace gpm::calib
