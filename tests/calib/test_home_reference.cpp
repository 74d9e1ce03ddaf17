// Tests of calib/home_reference.cpp: the home readings against the forward
// kinematics (a round trip); the reducer's errors by hand, and which of a
// fit's harmonics they are; moving their value at home out of the offsets
// keeps every link angle (against link_angle of the reading model before and
// after) and every closure residual of the readings the fit explains, moves
// dth by the error at home and widens its 1-sigma by the harmonics'; nothing
// moves where no reducer error was estimated.
#include "calib/home_reference.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "calib/paper_values.hpp"
#include "calib/residuals.hpp"
#include "models/kinematics.hpp"

namespace gpm::calib {
namespace {

constexpr double kGear = 10.0;

// The Table-5 robot's result with its 1-sigma and covariance, and a fit whose
// reducer error twice per motor revolution joints 1 and 3 carry, and once per
// joint revolution (estimated under a prior, on motor encoders) joint 1.
struct Case {
  HomePose home;
  Result result;
  MotionFit fit;
  MotionModel model;
};

Case make_case() {
  Case c;
  c.home.p = Robot{}.home;
  c.result.geometry = table5_actual();
  c.result.covariance = Eigen::Matrix<double, kNumParams, kNumParams>::Identity() * 1e-10;
  c.result.sigma.fill(1e-5);
  c.fit.harmonic[kReducerHarmonic] = {4e-5, 0.0, -2e-5, 1e-5, 0.0, 3e-5};  // a1 a2 a3 b1 b2 b3
  c.fit.harmonic_sigma[kReducerHarmonic] = {2e-6, NAN, 2e-6, 2e-6, NAN, 2e-6};
  c.fit.cyclic = {1e-4, 0.0, 0.0, -5e-5, 0.0, 0.0};
  c.fit.cyclic_sigma = {3e-6, NAN, 3e-6, 4e-6, NAN, 3e-6};
  c.model.gear_ratio = kGear;
  c.model.cyclic_prior_rad = 3e-4;
  c.model.estimate_cyclic = true;
  return c;
}

TEST(HomeReference, HomeReadingsStandAtHome) {
  const Geometry g = table5_actual();
  const std::optional<Eigen::Vector3d> r = home_readings(g, HomePose{Robot{}.home});
  ASSERT_TRUE(r);
  Eigen::Vector3d theta_a;
  for (int i = 0; i < 3; ++i) {
    EXPECT_GE((*r)[i], 0.0);
    EXPECT_LT((*r)[i], 2.0 * std::numbers::pi);
    theta_a[i] = (*r)[i] + g[dth(i)];
  }
  const auto fk = forward_kinematics(g, theta_a);
  ASSERT_TRUE(fk);
  EXPECT_LT((fk->p - Robot{}.home).norm(), 1e-9);
  EXPECT_FALSE(home_readings(g, HomePose{Eigen::Vector2d(5000.0, 0.0)}));  // out of reach
}

TEST(HomeReference, ReducerErrorByHand) {
  ReducerErrors e;
  e.h[kReducerHarmonic] = {1e-5, 0.0, 0.0, 2e-5, 0.0, 0.0};
  EXPECT_NEAR(reducer_error(e, 0, 0.3, kGear), 1e-5 * std::sin(6.0) + 2e-5 * std::cos(6.0), 1e-18);
  EXPECT_EQ(reducer_error(e, 1, 0.3, kGear), 0.0);
  e.h[kJointHarmonic] = {3e-5, 0.0, 0.0, -1e-5, 0.0, 0.0};  // once per joint revolution: the reading's own angle
  EXPECT_NEAR(reducer_error(e, 0, 0.3, kGear),
              1e-5 * std::sin(6.0) + 2e-5 * std::cos(6.0) + 3e-5 * std::sin(0.3) - 1e-5 * std::cos(0.3), 1e-18);
}

TEST(HomeReference, ReducerErrorsAreTheReducersHarmonicsOnly) {
  Case c = make_case();
  ReducerErrors e = reducer_errors(c.fit, c.model);
  EXPECT_EQ(e.h[kReducerHarmonic], c.fit.harmonic[kReducerHarmonic]);
  EXPECT_EQ(e.h[kJointHarmonic], c.fit.cyclic);  // estimated on motor encoders: the reducer's
  for (std::size_t k = 0; k < 6; ++k) {
    const double want = c.fit.cyclic_sigma[k];  // NaN where not estimated
    EXPECT_TRUE(std::isnan(want) ? std::isnan(e.sigma[kJointHarmonic][k]) : e.sigma[kJointHarmonic][k] == want) << k;
  }
  // Carried, not estimated, or read by encoders that turn with the joints: not the reducer's.
  for (const auto off : {+[](MotionModel& m) { m.estimate_cyclic = false; },
                         +[](MotionModel& m) { m.encoder_on_motor = false; },
                         +[](MotionModel& m) { m.gear_ratio = 1.0; }}) {
    MotionModel m = c.model;
    off(m);
    e = reducer_errors(c.fit, m);
    EXPECT_EQ(e.h[kJointHarmonic], (std::array<double, 6>{}));
    EXPECT_EQ(e.h[kReducerHarmonic], c.fit.harmonic[kReducerHarmonic]);
  }
  // The motor encoder's own error (once per motor revolution) is never the reducer's.
  c.fit.harmonic[1] = {1e-5, 1e-5, 1e-5, 1e-5, 1e-5, 1e-5};
  EXPECT_EQ(reducer_errors(c.fit, c.model).h[1], (std::array<double, 6>{}));
}

TEST(HomeReference, OffsetsAtHomeKeepEveryLinkAngleAndResidual) {
  Case c = make_case();
  const Result before = c.result;
  const ReducerErrors errors = reducer_errors(c.fit, c.model);
  ReadingModel zero_mean;
  zero_mean.gear_ratio = kGear;
  zero_mean.harmonic[kReducerHarmonic] = c.fit.harmonic[kReducerHarmonic];
  zero_mean.harmonic[kJointHarmonic] = c.fit.cyclic;
  ReadingModel referenced = zero_mean;
  const std::vector<Eigen::Vector3d> raw{{1.0, 3.1, 4.8}, {1.2, 2.9, 4.7}, {0.9, 3.2, 5.0}};
  std::vector<Eigen::Vector3d> used = raw;  // corrected by the zero-mean errors
  for (Eigen::Vector3d& m : used)
    for (int i = 0; i < 3; ++i) m[i] -= reducer_error(errors, i, m[i], kGear);
  const std::vector<Eigen::Vector3d> used_before = used;
  const auto moved = offsets_at_home(c.home, errors, kGear, c.result, used, &referenced);
  ASSERT_TRUE(moved);
  const Eigen::Vector3d r_home = *home_readings(before.geometry, c.home);
  for (int i = 0; i < 3; ++i) {
    const double e = reducer_error(errors, i, r_home[i], kGear);
    EXPECT_NEAR(moved->moved_rad[i], e, 1e-18);
    EXPECT_NEAR(c.result.geometry[dth(i)], before.geometry[dth(i)] - e, 1e-15);
    EXPECT_EQ(referenced.reducer_home_rad[static_cast<std::size_t>(i)], r_home[i]);
    // The link angle of every reading is the same: reading + offset - error, before and after.
    for (const Eigen::Vector3d& m : raw)
      EXPECT_NEAR(link_angle(zero_mean, i, m[i], 0.0, 0.0, 0.0) + before.geometry[dth(i)],
                  link_angle(referenced, i, m[i], 0.0, 0.0, 0.0) + c.result.geometry[dth(i)], 1e-15);
    // At home the referenced error is 0.
    EXPECT_NEAR(link_angle(referenced, i, r_home[i], 0.0, 0.0, 0.0), r_home[i], 1e-15);
  }
  EXPECT_NE(moved->moved_rad[0], 0.0);
  EXPECT_EQ(moved->moved_rad[1], 0.0);  // joint 2 has no such error
  // The readings the fit explains close the loop as before (the ML residual of eq. 38).
  for (std::size_t j = 0; j < used.size(); ++j) {
    double r0 = 0.0, r1 = 0.0;
    const MlResidual old_closure(used_before[j]), new_closure(used[j]);
    ASSERT_TRUE(old_closure(before.geometry.values.data(), &r0));
    ASSERT_TRUE(new_closure(c.result.geometry.values.data(), &r1));
    EXPECT_NEAR(r0, r1, 1e-12);
  }
  // dth_1 is as uncertain as before and the errors at home: sigma^2 + sum of (sa sin)^2 + (sb cos)^2.
  const double a = harmonic_angle(kReducerHarmonic, r_home[0], kGear, 0.0), aj = r_home[0];
  const double var = std::pow(2e-6 * std::sin(a), 2) + std::pow(2e-6 * std::cos(a), 2) +
                     std::pow(3e-6 * std::sin(aj), 2) + std::pow(4e-6 * std::cos(aj), 2);
  EXPECT_NEAR(c.result.sigma[dth(0)], std::sqrt(1e-10 + var), 1e-15);
  EXPECT_NEAR((*c.result.covariance)(dth(0), dth(0)), 1e-10 + var, 1e-22);
  EXPECT_EQ(c.result.sigma[dth(1)], 1e-5);
  EXPECT_NE(offsets_at_home_note(*moved).find("referenced to 0 at the home readings"), std::string::npos);
}

TEST(HomeReference, NothingMovesWithoutTheReducersError) {
  Case c = make_case();
  c.fit.harmonic[kReducerHarmonic].fill(0.0);
  c.model.estimate_cyclic = false;  // the error once per joint revolution carried
  const Result before = c.result;
  std::vector<Eigen::Vector3d> used{{1.0, 3.1, 4.8}};
  ReadingModel reading;
  EXPECT_FALSE(offsets_at_home(c.home, reducer_errors(c.fit, c.model), kGear, c.result, used, &reading));
  EXPECT_EQ(c.result.geometry.values, before.geometry.values);
  EXPECT_EQ(used.front(), Eigen::Vector3d(1.0, 3.1, 4.8));
  EXPECT_TRUE(std::isnan(reading.reducer_home_rad[0]));
  // Nor where the geometry cannot reach home.
  Case far = make_case();
  far.home.p = Eigen::Vector2d(5000.0, 0.0);
  EXPECT_FALSE(offsets_at_home(far.home, reducer_errors(far.fit, far.model), kGear, far.result, used, &reading));
}

}  // namespace
}  // namespace gpm::calib
