// E1, E2, E3 and ML residuals (calib/residuals.hpp) with analytic Jacobians,
// as ceres::SizedCostFunction: what Levenberg-Marquardt uses. The autodiff
// functors of calib/residuals.hpp stay the reference; the tests check both
// against each other and against central differences.
//
// The elbows come from cos and sin of the readings computed once per sample
// and of the offsets (cos(theta_m + dth) by the angle-sum formula), then the
// radical centre is models/closure.hpp's radical_centre.
//
// Derivation, from the closure of models/closure.hpp (one sample, chain k's
// parameters p in {xa_k, ya_k, la_k (or l_ac^k), dth_k (or l_as^k), lb_k}):
//
// The radical centre O and its power P solve, for i = 1..3,
//   F_i = |O - B_i|^2 - lb_i^2 - P = 0,                 w_i = O - B_i.
// Differentiating, with M the 3x3 matrix of rows [2 w_i^T, -1]:
//   M [dO; dP] = s,    s_i = 2 w_i . dB_i + 2 lb_i dlb_i.
// A parameter of chain k moves only B_k (and lb_k), so s = s_p e_k with
//   xa_k: dB_k = (1, 0)   ya_k: dB_k = (0, 1)   lb_k: dB_k = 0, s_p = 2 lb_k
//   la_k: dB_k = (cos theta_a, sin theta_a)   dth_k: dB_k = perp(B_k - A_k)
//   (decoupled, eq. 41: l_ac^k: (cos theta_m, sin theta_m),
//                       l_as^k: (-sin theta_m, cos theta_m))
// and s_p = 2 w_k . dB_k otherwise. Let (o_k, q_k) = M^-1 e_k (column k),
// solved like the centre itself relative to B1: -2 (B_i - B1) . o_k =
// [i = k] - [1 = k] for i = 2, 3, then q_k = 2 (O - B1) . o_k - [1 = k]. Then
//   dO/dp = s_p o_k,    dP/dp = s_p q_k.
// (-q_k is the barycentric coordinate of O in the elbow triangle: sum q = -1.)
//
// E2, E3 (one row g = P):   dg/dp = s_p q_k.
//
// E1 (row i, calib/residuals.hpp's E1LengthResidual): e_i = |w_i| - lb_i, with
//   dw_i = dO - [i = k] dB_k,
//   de_i = (w_i . dw_i) / |w_i| - [i = k, p = lb_k].
//
// ML: r = P / |g|, g_j = dP/d theta_m^j = q_j b_j, b_j = 2 w_j . perp(B_j - A_j)
// (a reading turns its own elbow about A_j). Differentiating q^T M = e_3^T:
//   dq_j = -2 v . o_j,   v = sum_i q_i dw_i = -dO - q_k dB_k,
//   db_j = 2 dw_j . perp(B_j - A_j) + [j = k] 2 w_j . perp(dB_k - dA_k),
//   dg_j = dq_j b_j + q_j db_j,
//   dr = dP / |g| - P (g . dg) / |g|^3.
#pragma once

#include <ceres/ceres.h>
#include <Eigen/Core>

#include "calib/problem.hpp"

namespace gpm::calib {

// cos and sin of one sample's three readings, computed once.
struct ReadingTrig {
  explicit ReadingTrig(const Eigen::Vector3d& theta_m);
  double c[3], s[3];
};

// E1 (eq. 36-37) as its three signed lengths e_i = |O - B_i| - lb_i per
// sample (|E1_i| = |e_i|, so sum e^2 = J1).
class E1Analytic final : public ceres::SizedCostFunction<3, kNumParams> {
 public:
  explicit E1Analytic(const Eigen::Vector3d& theta_m) : trig_(theta_m) {}
  bool Evaluate(double const* const* x, double* r, double** jac) const override;

 private:
  ReadingTrig trig_;
};

// E2 (eq. 38-39) in the coupled layout (decoupled = false) or E3 (eq. 41-43)
// in the decoupled layout: one row g = P per sample.
class PowerAnalytic final : public ceres::SizedCostFunction<1, kNumParams> {
 public:
  PowerAnalytic(const Eigen::Vector3d& theta_m, bool decoupled) : trig_(theta_m), decoupled_(decoupled) {}
  bool Evaluate(double const* const* x, double* r, double** jac) const override;

 private:
  ReadingTrig trig_;
  bool decoupled_;
};

// ML: r = P / |dP/d theta_m| per sample (radians).
class MlAnalytic final : public ceres::SizedCostFunction<1, kNumParams> {
 public:
  explicit MlAnalytic(const Eigen::Vector3d& theta_m) : trig_(theta_m) {}
  bool Evaluate(double const* const* x, double* r, double** jac) const override;

 private:
  ReadingTrig trig_;
};

// A new analytic cost function for one sample (the caller or a
// ceres::Problem owns it).
ceres::CostFunction* make_analytic_residual(Cost c, const Eigen::Vector3d& theta_m);

}  // namespace gpm::calib
