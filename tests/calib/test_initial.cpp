// Tests of calib/initial.cpp: the paper's reference-point procedure (section
// 3.2 step 3) reproduces the initial estimates printed in Table 2 (readings at
// (210, 245) of the section-3 actual robot, IK of home on the nominal model),
// and an unreachable reference point is an InputError.
#include "calib/initial.hpp"

#include <gtest/gtest.h>

#include "calib/paper_values.hpp"
#include "models/errors.hpp"
#include "models/kinematics.hpp"

namespace gpm::calib {
namespace {

TEST(Initial, ReproducesTable2InitialEstimates) {
  Robot actual;
  actual.geometry = section3_actual();
  actual.geometry[kLa1] = actual.geometry[kLa2] = actual.geometry[kLa3] = 244.0;  // Table 2: lengths and
  actual.geometry[kLb1] = actual.geometry[kLb2] = actual.geometry[kLb3] = 244.0;  // bases known (nominal)
  actual.geometry[kXa2] = 433.0;
  actual.geometry[kXa3] = 433.0;
  actual.geometry[kYa3] = 500.0;
  const Eigen::Vector3d theta_m0 =
      readings_from_active(actual.geometry, inverse_kinematics(actual.geometry, {210.0, 245.0}).theta_a);
  Robot model;  // nominal, reference point = home (216.5, 250)
  const Geometry g = offsets_from_reference(model, theta_m0, model.home);
  EXPECT_NEAR(g[kDth1], 1.00913, 5e-6);
  EXPECT_NEAR(g[kDth2], 0.97689, 5e-6);
  EXPECT_NEAR(g[kDth3], 1.02748, 5e-6);
  for (int i = 0; i < kDth1; ++i) EXPECT_EQ(g[i], model.geometry[i]);
}

TEST(Initial, ExactAtTheTrueReferencePoint) {
  Robot r;
  r.geometry[kDth1] = 0.3;
  r.geometry[kDth2] = -0.2;
  r.geometry[kDth3] = 0.1;
  const Eigen::Vector3d t = readings_from_active(r.geometry, inverse_kinematics(r.geometry, r.home).theta_a);
  const Geometry g = offsets_from_reference(r, t, r.home);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(g[dth(i)], r.geometry[dth(i)], 1e-12);
}

TEST(Initial, UnreachableReferenceIsInputError) {
  const Robot r;
  EXPECT_THROW(offsets_from_reference(r, Eigen::Vector3d::Zero(), {216.5, 900.0}), InputError);
}

}  // namespace
}  // namespace gpm::calib
