#include "calib/monitor/ml_sensitivity.hpp"

#include <cmath>

#include <ceres/jet.h>

#include "calib/residuals.hpp"

namespace gpm::calib::monitor {

bool ml_residual_and_gradient(const Geometry& g, const Eigen::Vector3d& theta_m, double& r,
                              ParamRow& dr_dparams) {
  using Jet = ceres::Jet<double, kNumParams>;
  Jet x[kNumParams];
  for (int i = 0; i < kNumParams; ++i) x[i] = Jet(g[i], i);
  Jet out;
  if (!MlResidual(theta_m)(x, &out)) return false;
  if (!std::isfinite(out.a)) return false;
  r = out.a;
  dr_dparams = out.v.transpose();
  return true;
}

}  // namespace gpm::calib::monitor
