// Straightforward scalar J1, J2, J3 written from the paper's equations (with
// docs/EQUATIONS.md), independent of the vectorised kernel, for the tests.
#pragma once

#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "models/parameters.hpp"

namespace gpm::calib::global::testing {

// End-effector from the elbows by eq. 32-33 as printed (squares restored in
// d_i, the division restored in y), evaluated with B1 moved to the origin
// (docs/EQUATIONS.md's advice for precision), then moved back.
inline Eigen::Vector2d reference_fk(const double xb[3], const double yb[3], const double lb[3]) {
  double X[3], Y[3], d[3];
  for (int i = 0; i < 3; ++i) {
    X[i] = xb[i] - xb[0];
    Y[i] = yb[i] - yb[0];
    d[i] = X[i] * X[i] + Y[i] * Y[i] - lb[i] * lb[i];  // eq. 32 (docs/EQUATIONS.md)
  }
  const double den = 2.0 * (X[0] * (Y[1] - Y[2]) + X[1] * (Y[2] - Y[0]) + X[2] * (Y[0] - Y[1]));
  const double x = (d[0] * (Y[1] - Y[2]) + d[1] * (Y[2] - Y[0]) + d[2] * (Y[0] - Y[1])) / den;
  const double y = (d[0] * (X[2] - X[1]) + d[1] * (X[0] - X[2]) + d[2] * (X[1] - X[0])) / den;
  return {xb[0] + x, yb[0] + y};
}

// J1 (eq. 36-37): passive angles by atan2 (eq. 34).
inline double reference_j1(const std::vector<Eigen::Vector3d>& tm, const Geometry& g) {
  double J = 0;
  for (const auto& t : tm) {
    double xb[3], yb[3], lb[3];
    for (int i = 0; i < 3; ++i) {
      const double th = t[i] + g[dth(i)];  // eq. 35
      xb[i] = g[xa(i)] + g[la(i)] * std::cos(th);  // eq. 30
      yb[i] = g[ya(i)] + g[la(i)] * std::sin(th);
      lb[i] = g[gpm::lb(i)];
    }
    const Eigen::Vector2d O = reference_fk(xb, yb, lb);
    for (int i = 0; i < 3; ++i) {
      const double thb = std::atan2(O.y() - yb[i], O.x() - xb[i]);
      const double ex = O.x() - xb[i] - lb[i] * std::cos(thb);
      const double ey = O.y() - yb[i] - lb[i] * std::sin(thb);
      J += ex * ex + ey * ey;
    }
  }
  return J;
}

// J2 (eq. 38-39, y_a^1 in row 1 per docs/EQUATIONS.md).
inline double reference_j2(const std::vector<Eigen::Vector3d>& tm, const Geometry& g) {
  double J = 0;
  for (const auto& t : tm) {
    double xb[3], yb[3], lb[3];
    for (int i = 0; i < 3; ++i) {
      xb[i] = g[xa(i)] + g[la(i)] * std::cos(t[i] + g[dth(i)]);
      yb[i] = g[ya(i)] + g[la(i)] * std::sin(t[i] + g[dth(i)]);
      lb[i] = g[gpm::lb(i)];
    }
    const Eigen::Vector2d O = reference_fk(xb, yb, lb);
    for (int i = 0; i < 3; ++i) {
      const double e = std::pow(O.x() - xb[i], 2) + std::pow(O.y() - yb[i], 2) - lb[i] * lb[i];
      J += e * e;
    }
  }
  return J;
}

// J3 (eq. 42-43) in the decoupled variables lac[i], las[i].
inline double reference_j3(const std::vector<Eigen::Vector3d>& tm, const Geometry& g,
                           const double lac[3], const double las[3]) {
  double J = 0;
  for (const auto& t : tm) {
    double xb[3], yb[3], lb[3];
    for (int i = 0; i < 3; ++i) {
      xb[i] = g[xa(i)] + (lac[i] * std::cos(t[i]) - las[i] * std::sin(t[i]));
      yb[i] = g[ya(i)] + (lac[i] * std::sin(t[i]) + las[i] * std::cos(t[i]));
      lb[i] = g[gpm::lb(i)];
    }
    const Eigen::Vector2d O = reference_fk(xb, yb, lb);
    for (int i = 0; i < 3; ++i) {
      const double e = std::pow(O.x() - xb[i], 2) + std::pow(O.y() - yb[i], 2) - lb[i] * lb[i];
      J += e * e;
    }
  }
  return J;
}

}  // namespace gpm::calib::global::testing
