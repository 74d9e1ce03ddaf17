// The paper's error functions evaluated at one geometry for recorded
// readings, independently of the solvers: J1 (eq. 37) and J2 = J3 (eq. 39,
// 43; equal at the same geometry, eq. 41 only re-parameterises l_a, dth).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "models/parameters.hpp"

namespace gpm::paper {

struct ClosureCosts {
  double j1 = 0.0;   // sum over samples and chains of (|O - B_i| - l_b^i)^2 (mm^2)
  double j23 = 0.0;  // sum over samples and chains of (|O - B_i|^2 - (l_b^i)^2)^2 (mm^4)
};

// J1 and J2 (= J3) of geometry g for readings theta_m, with O the radical
// centre of the three passive circles (eq. 32-33 corrected, errata) and
// B_i = A_i + l_a^i u(theta_m^i + dth^i) (eq. 30, 35). Infinite when a
// sample has no forward kinematics.
ClosureCosts closure_costs(const Geometry& g, const std::vector<Eigen::Vector3d>& theta_m);

}  // namespace gpm::paper
