// Tests of calib/parameterization.cpp: J3's l_ac, l_as round trip through
// eq. 44 (docs/EQUATIONS.md: atan2, hypot) for offsets in every quadrant, the Jacobian
// against central differences, and the free-set rule of J3.
#include "calib/parameterization.hpp"

#include <gtest/gtest.h>

#include "calib/paper_values.hpp"
#include "models/errors.hpp"

namespace gpm::calib {
namespace {

TEST(Parameterization, RoundTripThroughEq44InEveryQuadrant) {
  for (double d : {0.01, 1.0, 2.5, -2.5, -0.7}) {
    Geometry g = table5_actual();
    g[kDth2] = d;
    const ParamVector x = to_solver(g, Cost::kJ3);
    EXPECT_NEAR(x[kLa2], g[kLa2] * std::cos(d), 1e-12);
    EXPECT_NEAR(x[kDth2], g[kLa2] * std::sin(d), 1e-12);
    const Geometry b = from_solver(x, Cost::kJ3);
    for (int i = 0; i < kNumParams; ++i) EXPECT_NEAR(b[i], g[i], 1e-12) << param_name(i) << " at dth " << d;
    EXPECT_EQ(from_solver(to_solver(g, Cost::kML), Cost::kML), g);
  }
}

TEST(Parameterization, JacobianMatchesCentralDifferences) {
  const ParamVector x = to_solver(section3_actual(), Cost::kJ3);
  const auto T = geometry_jacobian(x, Cost::kJ3);
  for (int k = 0; k < kNumParams; ++k) {
    ParamVector xp = x, xm = x;
    xp[static_cast<size_t>(k)] += 1e-6;
    xm[static_cast<size_t>(k)] -= 1e-6;
    const Geometry gp = from_solver(xp, Cost::kJ3), gm = from_solver(xm, Cost::kJ3);
    for (int i = 0; i < kNumParams; ++i) EXPECT_NEAR(T(i, k), (gp[i] - gm[i]) / 2e-6, 1e-7) << i << "," << k;
  }
}

TEST(Parameterization, J3NeedsLengthAndOffsetFreeTogether) {
  EXPECT_THROW(check_free_set(parse_param_list("dth1,dth2,dth3", "t"), Cost::kJ3), InputError);
  EXPECT_NO_THROW(check_free_set(parse_param_list("dth1,dth2,dth3", "t"), Cost::kJ2));
  EXPECT_NO_THROW(check_free_set(default_free_mask(), Cost::kJ3));
}

}  // namespace
}  // namespace gpm::calib
