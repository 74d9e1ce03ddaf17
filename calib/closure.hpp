// Loop-closure geometry of one sample, templated on the scalar so that Ceres
// can differentiate it (paper eq. 30-35, 41-42; ERRATA). Millimetres, radians.
//
// The solver's parameter vector x has the 15 slots of Geometry. In the
// "coupled" layout (J1, J2, ML) x[la(i)] = l_a^i and x[dth(i)] = dth^i; in the
// "decoupled" layout of J3 (eq. 41-42) the same slots hold l_ac^i = l_a^i cos dth^i
// and l_as^i = l_a^i sin dth^i (see calib/parameterization.hpp).
#pragma once

#include <cmath>

#include "models/parameters.hpp"

namespace gpm::calib {

// Elbows, radical centre, closure power and its gradient w.r.t. the readings.
template <typename T>
struct Closure {
  T Bx[3], By[3];  // elbows B_i (eq. 30, or eq. 41 in the decoupled layout)
  T Ox, Oy;        // radical centre O of the three passive circles (eq. 32-33, ERRATA)
  T P;             // power |O - B_i|^2 - lb_i^2, equal for i = 1..3 (ERRATA); 0 when the loops close
  T dP[3];         // dP / d theta_m^k, k = 1..3 (mm^2 / rad); valid when with_gradient
  bool ok = true;  // false when the elbows are collinear (no radical centre)
};

// Computes the closure of readings theta_m under parameters x (layout as
// above); with_gradient adds dP/d theta_m by implicit differentiation.
template <typename T>
Closure<T> closure(const T* x, const double* theta_m, bool decoupled, bool with_gradient) {
  using std::cos;
  using std::sin;
  Closure<T> c;
  T Ax[3], Ay[3];
  for (int i = 0; i < 3; ++i) {
    Ax[i] = x[xa(i)];
    Ay[i] = x[ya(i)];
    if (decoupled) {
      // eq. 41: l_a cos(theta_m + dth) = l_ac cos theta_m - l_as sin theta_m, etc.
      const double cm = std::cos(theta_m[i]), sm = std::sin(theta_m[i]);
      c.Bx[i] = Ax[i] + x[la(i)] * cm - x[dth(i)] * sm;
      c.By[i] = Ay[i] + x[la(i)] * sm + x[dth(i)] * cm;
    } else {
      // eq. 30 and 35: theta_a = theta_m + dth.
      const T theta_a = theta_m[i] + x[dth(i)];
      c.Bx[i] = Ax[i] + x[la(i)] * cos(theta_a);
      c.By[i] = Ay[i] + x[la(i)] * sin(theta_a);
    }
  }
  // eq. 32 relative to B1 (u = O - B1): 2 (B_i - B1) . u = |B_i - B1|^2 + lb1^2 - lb_i^2;
  // eq. 33 is Cramer's rule for it (ERRATA restores the squares and the division).
  const T d2x = c.Bx[1] - c.Bx[0], d2y = c.By[1] - c.By[0];
  const T d3x = c.Bx[2] - c.Bx[0], d3y = c.By[2] - c.By[0];
  const T lb1_sq = x[lb(0)] * x[lb(0)];
  const T r2 = 0.5 * (d2x * d2x + d2y * d2y + lb1_sq - x[lb(1)] * x[lb(1)]);
  const T r3 = 0.5 * (d3x * d3x + d3y * d3y + lb1_sq - x[lb(2)] * x[lb(2)]);
  const T det = d2x * d3y - d2y * d3x;
  using std::abs;
  const T scale = d2x * d2x + d2y * d2y + d3x * d3x + d3y * d3y;
  if (!(abs(det) > 1e-12 * scale)) {
    c.ok = false;
    c.Ox = c.Oy = c.P = T(0.0);
    for (auto& g : c.dP) g = T(0.0);
    return c;
  }
  const T ux = (r2 * d3y - r3 * d2y) / det;
  const T uy = (d2x * r3 - d3x * r2) / det;
  c.Ox = c.Bx[0] + ux;
  c.Oy = c.By[0] + uy;
  c.P = ux * ux + uy * uy - lb1_sq;
  if (!with_gradient) return c;
  // Implicit differentiation of |O - B_i|^2 - lb_i^2 - P = 0 (i = 1..3) with
  // w_i = O - B_i: 2 w_i . dO - dP = 2 w_i . dB_i. Subtracting row 1 gives
  // -2 (B_i - B1) . dO = b_i - b_1 (i = 2, 3), then dP = 2 w_1 . dO - b_1.
  // A reading moves only its own elbow: dB_k / d theta_m^k = perp(B_k - A_k)
  // (both layouts), so b_k = 2 w_k . perp(B_k - A_k) per unit d theta_m^k.
  T b[3];
  for (int k = 0; k < 3; ++k) {
    const T wx = c.Ox - c.Bx[k], wy = c.Oy - c.By[k];
    const T px = -(c.By[k] - Ay[k]), py = c.Bx[k] - Ax[k];
    b[k] = 2.0 * (wx * px + wy * py);
  }
  for (int k = 0; k < 3; ++k) {
    // right-hand side (b_2 - b_1, b_3 - b_1) for a unit change of theta_m^k
    const T rhs2 = (k == 1 ? b[1] : T(0.0)) - (k == 0 ? b[0] : T(0.0));
    const T rhs3 = (k == 2 ? b[2] : T(0.0)) - (k == 0 ? b[0] : T(0.0));
    // solve -2 [d2; d3] dO = rhs
    const T dOx = -(rhs2 * d3y - rhs3 * d2y) / (2.0 * det);
    const T dOy = -(d2x * rhs3 - d3x * rhs2) / (2.0 * det);
    c.dP[k] = 2.0 * (ux * dOx + uy * dOy) - (k == 0 ? b[0] : T(0.0));
  }
  return c;
}

}  // namespace gpm::calib
