// The closure error functions J1, J2, J3 of paper section 3 over a block of
// candidate parameter sets at once: the inner loop runs over candidates on
// structure-of-arrays data so the compiler vectorises it, and the readings'
// sin/cos are computed once per sample set.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "calib/problem.hpp"

namespace gpm::calib::global {

// cos and sin of every encoder reading, computed once (eq. 41).
struct SampleTable {
  long size = 0;
  std::vector<double> cos_m[3];
  std::vector<double> sin_m[3];
};

// The table of readings theta_m (rad) per sample.
SampleTable make_sample_table(const std::vector<Eigen::Vector3d>& theta_m);

// Kernel variables of one candidate, in the decoupled form of eq. 41:
// base joints, l_ac = la cos dth, l_as = la sin dth, passive links.
enum KernelVar : int {
  kKxa1, kKya1, kKxa2, kKya2, kKxa3, kKya3,
  kKlac1, kKlac2, kKlac3,
  kKlas1, kKlas2, kKlas3,
  kKlb1, kKlb2, kKlb3,
  kNumKernelVars
};

// Candidates per kernel block (the vectorised inner loop's trip count).
inline constexpr int kKernelBlock = 16;

// Closure cost of kKernelBlock candidates. kv[v * kKernelBlock + c] is kernel
// variable v of candidate c; writes J[c].
//
// Per sample j and chain i (eq. 30 with eq. 41): the elbow
//   B_i = A_i + (l_ac c_i - l_as s_i, l_as c_i + l_ac s_i),
//   c_i = cos(theta_m_i), s_i = sin(theta_m_i).
// The end-effector O is the radical centre of the three passive circles
// (eq. 32-33 with the squares restored, docs/EQUATIONS.md), solved relative to B1:
//   2 (B_i - B1) . u = |B_i - B1|^2 + lb1^2 - lb_i^2, i = 2, 3;  O = B1 + u.
// Rows e_i = |O - B_i|^2 - lb_i^2 are E2 (eq. 38, y_a^1 in row 1 per docs/EQUATIONS.md)
// or, in the decoupled variables, E3 (eq. 42):
//   J2 = J3 = sum_j sum_i e_i^2  (eq. 39, 43).
// E1 (eq. 36) with theta_b_i = atan2 of O - B_i (eq. 34) has row i equal to
// (O - B_i)(1 - lb_i / r_i), r_i = |O - B_i|, so |E1 row i| = |r_i - lb_i| =
// |e_i| / (r_i + lb_i), the last form free of cancellation:
//   J1 = sum_j sum_i (e_i / (r_i + lb_i))^2  (eq. 37).
// (docs/EQUATIONS.md: at the radical centre the three e_i are equal per sample; the sum
// over the three rows is kept so values compare with paper Table 6.)
// Collinear elbows (no radical centre) give J = +inf. cost must be kJ1, kJ2
// or kJ3 (kJ2 and kJ3 share the formula; they differ in the variables).
void closure_cost_block(Cost cost, const SampleTable& t, const double* kv, double* J);

// The same for one candidate (kv[v] is kernel variable v), without the
// block's vector lanes: for callers that evaluate one point at a time.
double closure_cost_single(Cost cost, const SampleTable& t, const double* kv);

}  // namespace gpm::calib::global
