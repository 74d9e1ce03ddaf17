// The solver's parameter vector for each error function: the 15 geometry
// values, except that J3 holds l_ac^i = l_a^i cos dth^i in slot la(i) and
// l_as^i = l_a^i sin dth^i in slot dth(i) (eq. 41-42), mapped back by eq. 44
// as corrected in docs/EQUATIONS.md: l_a = hypot(l_ac, l_as), dth = atan2(l_as, l_ac).
#pragma once

#include <array>

#include <Eigen/Core>

#include "calib/problem.hpp"

namespace gpm::calib {

using ParamVector = std::array<double, kNumParams>;

// Solver vector of geometry g for cost c.
ParamVector to_solver(const Geometry& g, Cost c);

// Geometry of solver vector x for cost c (eq. 44 per docs/EQUATIONS.md for J3).
Geometry from_solver(const ParamVector& x, Cost c);

// d(geometry) / d(solver vector) at x (identity except the J3 pairs), to carry
// covariances from the solver's variables to the geometry.
Eigen::Matrix<double, kNumParams, kNumParams> geometry_jacobian(const ParamVector& x, Cost c);

// Throws InputError when cost c cannot estimate the free set: J3 decouples
// l_a^i and dth^i, so both must be free or both fixed.
void check_free_set(const FreeMask& free, Cost c);

}  // namespace gpm::calib
