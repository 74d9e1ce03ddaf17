// Residuals of the error functions J1, J2, J3 and ML for one sample (paper
// section 3.1; docs/EQUATIONS.md), as Ceres autodiff functors over the 15-slot parameter
// vector of models/closure.hpp. These functors are the reference; the solver
// uses the same residuals with analytic Jacobians (calib/analytic_residuals.hpp).
//
// Honest accounting (docs/EQUATIONS.md): with the radical centre of eq. 32-33 as forward
// kinematics, the three rows of E2 (and of E3) are the same number g = P for
// every sample, so J2 = J3 = 3 * sum_j g_j^2. The solver uses ONE row g per
// sample (same minimiser, a Jacobian whose rank and covariance are not
// inflated by copies); paper_cost() multiplies back to the paper's J.
#pragma once

#include <ceres/ceres.h>
#include <Eigen/Core>

#include "models/closure.hpp"
#include "calib/problem.hpp"

namespace gpm::calib {

// The three encoder readings theta_m (rad) of one sample, which every residual functor below holds.
struct SampleReadings {
  explicit SampleReadings(const Eigen::Vector3d& theta_m) : theta_m_{theta_m[0], theta_m[1], theta_m[2]} {}
  double theta_m_[3];
};

// E1 (eq. 36-37): for each chain i, with O the radical centre and theta_b^i
// from eq. 34 (atan2),
//   E1_i = O - A_i - l_a^i u(theta_m^i + dth^i) - l_b^i u(theta_b^i)
//        = (|O - B_i| - l_b^i) (O - B_i) / |O - B_i|,      u(t) = (cos t, sin t).
// Six rows per sample; J1 = sum_j |E1_j|^2. The paper's form, kept as the
// reference of eq. 36; the solver uses E1LengthResidual below.
//
// E1 as the solver uses it: the signed length of each E1_i,
//   e_i = |O - B_i| - l_b^i,       E1_i = e_i (O - B_i) / |O - B_i|,
// three rows per sample. |E1_i| = |e_i|, so sum e^2 = J1 at every parameter
// set: the same cost and minimiser as eq. 36's six rows, with half the rows
// (each E1_i is a vector along O - B_i, whose direction carries no error).
//
// Both as one functor: kSixRows, the vectors E1_i (eq. 36); else their signed lengths e_i.
template <bool kSixRows>
struct ChainGapResidual : SampleReadings {
  using SampleReadings::SampleReadings;
  template <typename T>
  bool operator()(const T* x, T* r) const {
    using std::sqrt;
    const Closure<T> c = closure(x, theta_m_, false, false);
    if (!c.ok) return false;
    for (int i = 0; i < 3; ++i) {
      const T wx = c.Ox - c.Bx[i], wy = c.Oy - c.By[i];
      const T dist = sqrt(wx * wx + wy * wy);
      const T e = dist - x[lb(i)];
      if constexpr (kSixRows) {
        const T f = e / dist;
        r[2 * i] = f * wx;
        r[2 * i + 1] = f * wy;
      } else {
        r[i] = e;
      }
    }
    return true;
  }
};
using E1Residual = ChainGapResidual<true>;
using E1LengthResidual = ChainGapResidual<false>;

// E2 (eq. 38, row 1 with y_a^1 per docs/EQUATIONS.md): for each chain i,
//   E2_i = (x - x_a^i - l_a^i cos(theta_m^i + dth^i))^2
//        + (y - y_a^i - l_a^i sin(theta_m^i + dth^i))^2 - (l_b^i)^2 = |O - B_i|^2 - (l_b^i)^2,
// which equals the power P of the radical centre for all three i. One row g = P
// per sample (mm^2); J2 = 3 sum_j g_j^2.
//
// E3 (eq. 42-43): E2 with the products decoupled (eq. 41) into
// l_ac^i = l_a^i cos dth^i and l_as^i = l_a^i sin dth^i, so that
//   B_i = A_i + (l_ac^i cos theta_m^i - l_as^i sin theta_m^i,
//                l_ac^i sin theta_m^i + l_as^i cos theta_m^i),
// and E3_i = |O - B_i|^2 - (l_b^i)^2 = P for all i. One row g = P per sample;
// J3 = 3 sum_j g_j^2. l_a, dth are recovered by eq. 44 per docs/EQUATIONS.md:
// l_a = hypot(l_ac, l_as), dth = atan2(l_as, l_ac).
//
// Both as one functor: the power P of the radical centre, one row per sample,
// with the active links coupled (E2: l_a, dth) or decoupled (E3: l_ac, l_as).
template <bool kDecoupled>
struct PowerResidual : SampleReadings {
  using SampleReadings::SampleReadings;
  template <typename T>
  bool operator()(const T* x, T* r) const {
    const Closure<T> c = closure(x, theta_m_, kDecoupled, false);
    r[0] = c.P;
    return c.ok;
  }
};
using E2Residual = PowerResidual<false>;
using E3Residual = PowerResidual<true>;

// ML (ours): the closure residual divided by the norm of its gradient with
// respect to the three readings,
//   r = P / |dP / d theta_m|          (radians),
// with dP/d theta_m by implicit differentiation (models/closure.hpp). To first
// order a reading error eps changes P by grad . eps, so r is the smallest
// reading correction that closes the loops (a Sampson distance): with iid
// encoder noise of sigma, r ~ N(0, sigma^2) and sum r^2 is the negative
// log-likelihood, so least squares is the maximum-likelihood estimate. r is
// invariant under the similarity gauge at every point (P and its gradient
// scale alike), which calib/identifiability.hpp relies on.
struct MlResidual : SampleReadings {
  using SampleReadings::SampleReadings;
  template <typename T>
  bool operator()(const T* x, T* r) const {
    using std::sqrt;
    const Closure<T> c = closure(x, theta_m_, false, true);
    if (!c.ok) return false;
    const T g2 = c.dP[0] * c.dP[0] + c.dP[1] * c.dP[1] + c.dP[2] * c.dP[2];
    if (!(g2 > T(0.0))) return false;
    r[0] = c.P / sqrt(g2);
    return true;
  }
};

// Rows per sample that the solver uses for cost c (3 for J1: E1LengthResidual; else 1).
int residual_rows(Cost c);

// True when cost c works in the decoupled layout l_ac, l_as (J3).
bool is_decoupled(Cost c);

// A new cost function for one sample with the analytic Jacobian of
// calib/analytic_residuals.hpp (what LM and identifiability use; the caller
// or a ceres::Problem owns it).
ceres::CostFunction* make_residual(Cost c, const Eigen::Vector3d& theta_m);

// The same with Ceres automatic differentiation of the functors above: the
// reference the analytic Jacobians are tested against.
ceres::CostFunction* make_autodiff_residual(Cost c, const Eigen::Vector3d& theta_m);

// The paper's J (eq. 37, 39, 43; sum of squares for ML) from the sum of
// squares of the solver's rows: J2 = J3 = 3 sum g^2 (docs/EQUATIONS.md), J1 and ML as is.
double paper_cost(Cost c, double sum_of_squares);

}  // namespace gpm::calib
