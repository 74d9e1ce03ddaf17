// The loop closure of the 3-RRR mechanism, templated on the scalar so that
// doubles (forward kinematics, identifiability) and Ceres Jets (the
// residuals of calib/residuals.hpp) run the same code. Millimetres, radians.
// docs/EQUATIONS.md maps each equation to this file.
//
// radical_centre(): the end-effector O as the radical centre of the three
// passive circles (centre B_i, radius l_b^i), paper eq. 32-33 corrected:
//   d_i = (x_b^i)^2 + (y_b^i)^2 - (l_b^i)^2   (the paper drops these squares),
// and the linear system of eq. 32 is solved by Cramer's rule (the paper's y
// formula lacks its division) relative to B1 for precision: with u = O - B1,
//   2 (B_i - B1) . u = |B_i - B1|^2 + (l_b^1)^2 - (l_b^i)^2,   i = 2, 3.
// Its power P = |O - B_i|^2 - (l_b^i)^2 is the same for i = 1..3 and is zero
// when the readings close the loops exactly.
//
// closure(): elbows from a 15-slot parameter vector x (Geometry's order) and
// the readings theta_m, then the radical centre, and optionally dP/d theta_m.
// In the "coupled" layout x[la(i)] = l_a^i and x[dth(i)] = dth^i (eq. 30, 35:
// theta_a = theta_m + dth); in the "decoupled" layout of J3 (eq. 41-42) the
// same slots hold l_ac^i = l_a^i cos dth^i and l_as^i = l_a^i sin dth^i.
#pragma once

#include <cmath>

#include "models/parameters.hpp"

namespace gpm {

// Radical centre of three circles and the quantities derived on the way.
template <typename T>
struct RadicalCentre {
  T Ox, Oy;        // the radical centre O
  T ux, uy;        // O - B1
  T d2x, d2y;      // B2 - B1
  T d3x, d3y;      // B3 - B1
  T det;           // d2 x d3 (twice the signed area of the elbow triangle)
  T P;             // power |O - B_i|^2 - lb_i^2, equal for i = 1..3
  bool ok = true;  // false when the elbows are collinear (|det| <= 1e-12 (|d2|^2 + |d3|^2))
};

// Radical centre of the circles (B_i, lb_i), i = 1..3 (eq. 32-33, corrected
// as above). When the elbows are collinear: ok = false and O, u, P are 0.
template <typename T>
RadicalCentre<T> radical_centre(const T Bx[3], const T By[3], const T lb[3]) {
  using std::abs;
  RadicalCentre<T> c;
  c.d2x = Bx[1] - Bx[0], c.d2y = By[1] - By[0];
  c.d3x = Bx[2] - Bx[0], c.d3y = By[2] - By[0];
  const T lb1_sq = lb[0] * lb[0];
  const T r2 = 0.5 * (c.d2x * c.d2x + c.d2y * c.d2y + lb1_sq - lb[1] * lb[1]);
  const T r3 = 0.5 * (c.d3x * c.d3x + c.d3y * c.d3y + lb1_sq - lb[2] * lb[2]);
  c.det = c.d2x * c.d3y - c.d2y * c.d3x;
  const T scale = c.d2x * c.d2x + c.d2y * c.d2y + c.d3x * c.d3x + c.d3y * c.d3y;
  if (!(abs(c.det) > 1e-12 * scale)) {
    c.ok = false;
    c.Ox = c.Oy = c.ux = c.uy = c.P = T(0.0);
    return c;
  }
  c.ux = (r2 * c.d3y - r3 * c.d2y) / c.det;
  c.uy = (c.d2x * r3 - c.d3x * r2) / c.det;
  c.Ox = Bx[0] + c.ux;
  c.Oy = By[0] + c.uy;
  c.P = c.ux * c.ux + c.uy * c.uy - lb1_sq;
  return c;
}

// Passive angle theta_b^i of the link from B_i to O (eq. 34 with the
// two-argument atan2, in (-pi, pi]).
template <typename T>
T passive_angle(const T& Ox, const T& Oy, const T& Bx, const T& By) {
  using std::atan2;
  return atan2(Oy - By, Ox - Bx);
}

// Elbows, radical centre, closure power and its gradient w.r.t. the readings.
template <typename T>
struct Closure {
  T Ax[3], Ay[3];  // base joints A_i
  T Bx[3], By[3];  // elbows B_i (eq. 30, or eq. 41 in the decoupled layout)
  RadicalCentre<T> rc;
  T Ox, Oy;        // radical centre O (= rc.Ox, rc.Oy)
  T P;             // power of O (= rc.P); 0 when the loops close
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
  T lb_[3];
  for (int i = 0; i < 3; ++i) {
    c.Ax[i] = x[xa(i)];
    c.Ay[i] = x[ya(i)];
    lb_[i] = x[lb(i)];
    if (decoupled) {
      // eq. 41: l_a cos(theta_m + dth) = l_ac cos theta_m - l_as sin theta_m, etc.
      const double cm = std::cos(theta_m[i]), sm = std::sin(theta_m[i]);
      c.Bx[i] = c.Ax[i] + x[la(i)] * cm - x[dth(i)] * sm;
      c.By[i] = c.Ay[i] + x[la(i)] * sm + x[dth(i)] * cm;
    } else {
      // eq. 30 and 35: theta_a = theta_m + dth.
      const T theta_a = theta_m[i] + x[dth(i)];
      c.Bx[i] = c.Ax[i] + x[la(i)] * cos(theta_a);
      c.By[i] = c.Ay[i] + x[la(i)] * sin(theta_a);
    }
  }
  c.rc = radical_centre(c.Bx, c.By, lb_);
  c.ok = c.rc.ok;
  c.Ox = c.rc.Ox;
  c.Oy = c.rc.Oy;
  c.P = c.rc.P;
  for (auto& g : c.dP) g = T(0.0);
  if (!c.ok || !with_gradient) return c;
  // Implicit differentiation of |O - B_i|^2 - lb_i^2 - P = 0 (i = 1..3) with
  // w_i = O - B_i: 2 w_i . dO - dP = 2 w_i . dB_i. Subtracting row 1 gives
  // -2 (B_i - B1) . dO = b_i - b_1 (i = 2, 3), then dP = 2 w_1 . dO - b_1.
  // A reading moves only its own elbow: dB_k / d theta_m^k = perp(B_k - A_k)
  // (both layouts), so b_k = 2 w_k . perp(B_k - A_k) per unit d theta_m^k.
  const RadicalCentre<T>& r = c.rc;
  T b[3];
  for (int k = 0; k < 3; ++k) {
    const T wx = c.Ox - c.Bx[k], wy = c.Oy - c.By[k];
    const T px = -(c.By[k] - c.Ay[k]), py = c.Bx[k] - c.Ax[k];
    b[k] = 2.0 * (wx * px + wy * py);
  }
  for (int k = 0; k < 3; ++k) {
    // right-hand side (b_2 - b_1, b_3 - b_1) for a unit change of theta_m^k
    const T rhs2 = (k == 1 ? b[1] : T(0.0)) - (k == 0 ? b[0] : T(0.0));
    const T rhs3 = (k == 2 ? b[2] : T(0.0)) - (k == 0 ? b[0] : T(0.0));
    // solve -2 [d2; d3] dO = rhs
    const T dOx = -(rhs2 * r.d3y - rhs3 * r.d2y) / (2.0 * r.det);
    const T dOy = -(r.d2x * rhs3 - r.d3x * rhs2) / (2.0 * r.det);
    c.dP[k] = 2.0 * (r.ux * dOx + r.uy * dOy) - (k == 0 ? b[0] : T(0.0));
  }
  return c;
}

}  // namespace gpm
