#include "calib/residuals.hpp"

#include "calib/analytic_residuals.hpp"

namespace gpm::calib {

int residual_rows(Cost c) { return c == Cost::kJ1 ? 3 : 1; }

bool is_decoupled(Cost c) { return c == Cost::kJ3; }

ceres::CostFunction* make_residual(Cost c, const Eigen::Vector3d& theta_m) {
  return make_analytic_residual(c, theta_m);
}

ceres::CostFunction* make_autodiff_residual(Cost c, const Eigen::Vector3d& theta_m) {
  switch (c) {
    case Cost::kJ1:
      return new ceres::AutoDiffCostFunction<E1LengthResidual, 3, kNumParams>(new E1LengthResidual(theta_m));
    case Cost::kJ2:
      return new ceres::AutoDiffCostFunction<E2Residual, 1, kNumParams>(new E2Residual(theta_m));
    case Cost::kJ3:
      return new ceres::AutoDiffCostFunction<E3Residual, 1, kNumParams>(new E3Residual(theta_m));
    case Cost::kML:
      return new ceres::AutoDiffCostFunction<MlResidual, 1, kNumParams>(new MlResidual(theta_m));
  }
  return nullptr;
}

double paper_cost(Cost c, double sum_of_squares) {
  return (c == Cost::kJ2 || c == Cost::kJ3) ? 3.0 * sum_of_squares : sum_of_squares;
}

}  // namespace gpm::calib
