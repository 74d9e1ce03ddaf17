// Tests of calib/reading_model.cpp: the reading sigma of an encoder, the link
// angle of a reading by hand and against the calibration's own correction
// (calib/motion_correction.hpp correct_readings), the reading of a link angle
// (its inverse), and the range checks.
#include "calib/reading_model.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "calib/motion_correction.hpp"
#include "models/errors.hpp"

namespace gpm::calib {
namespace {

TEST(ReadingModel, ReadingSigmaIsQuantisationAndNoiseInQuadrature) {
  const double q17 = 2.0 * std::numbers::pi / 131072.0;
  EXPECT_EQ(encoder_step_rad(17), q17);
  EXPECT_EQ(encoder_step_rad(0), 0.0);
  EXPECT_NEAR(reading_sigma(q17, 0.0), q17 / std::sqrt(12.0), 1e-18);
  EXPECT_DOUBLE_EQ(reading_sigma(0.0, 3e-5), 3e-5);
  EXPECT_NEAR(reading_sigma(q17, 1e-5), std::hypot(q17 / std::sqrt(12.0), 1e-5), 1e-18);
  // Averaging n readings divides the noise's variance by n, not the step's.
  EXPECT_NEAR(reading_sigma(q17, 2e-5, 4.0), std::hypot(q17 / std::sqrt(12.0), 1e-5), 1e-18);
  ReadingModel m;
  m.encoder_bits = 17;
  m.noise_rad = 1e-5;
  EXPECT_EQ(reading_sigma(m), reading_sigma(q17, 1e-5));
}

// Every effect at once, worked by hand: theta = 1 rad, omega = 2 rad/s,
// tau_t = 3 N m on the pressed flank (+1), gear ratio 10.
TEST(ReadingModel, LinkAngleByHand) {
  ReadingModel m;
  m.skew_s = {1e-4, 0.0, 0.0};
  m.compliance_rad_per_Nm = {2e-5, 0.0, 0.0};
  m.backlash_rad = {3e-4, 0.0, 0.0};
  m.gear_ratio = 10.0;
  m.harmonic[0] = {1e-5, 0, 0, 2e-5, 0, 0};  // once per joint revolution: a sin(1) + b cos(1)
  m.harmonic[2] = {0, 0, 0, 4e-6, 0, 0};     // twice per motor revolution: b cos(20)
  const double want = 1.0 + 2e-4 - 6e-5 - 3e-4 - (1e-5 * std::sin(1.0) + 2e-5 * std::cos(1.0)) - 4e-6 * std::cos(20.0);
  EXPECT_NEAR(link_angle(m, 0, 1.0, 2.0, 3.0, 1.0), want, 1e-15);
  // The other joints carry none of it; the flank unknown (0) takes no backlash.
  EXPECT_EQ(link_angle(m, 1, 1.0, 2.0, 3.0, 1.0), 1.0);
  EXPECT_NEAR(link_angle(m, 0, 1.0, 2.0, 3.0, 0.0) - link_angle(m, 0, 1.0, 2.0, 3.0, 1.0), 3e-4, 1e-15);
  EXPECT_EQ(harmonic_angle(0, 0.5, 10.0, 24.0), 0.5);
  EXPECT_EQ(harmonic_angle(1, 0.5, 10.0, 24.0), 5.0);
  EXPECT_EQ(harmonic_angle(2, 0.5, 10.0, 24.0), 10.0);
  EXPECT_EQ(harmonic_angle(kCoggingHarmonic, 0.5, 10.0, 24.0), 120.0);  // P N theta_m
}

// The motor's cogging twists the transmission by a sin(P N theta_m) + b
// cos(P N theta_m), worked by hand at P = 24, N = 10; it is no reducer error,
// so nothing references it at home.
TEST(ReadingModel, CoggingIsAHarmonicOfTheMotorAngle) {
  ReadingModel m;
  m.gear_ratio = 10.0;
  m.cogging_periods = 24.0;
  m.harmonic[kCoggingHarmonic] = {0, 3e-6, 0, 0, -5e-6, 0};  // joint 2: a = 3e-6, b = -5e-6
  m.reducer_home_rad = {0.3, 0.3, 0.3};
  const double theta_m = 0.7, a = 24.0 * 10.0 * 0.7;
  EXPECT_NEAR(link_angle(m, 1, theta_m, 0.0, 0.0, 0.0), theta_m - (3e-6 * std::sin(a) - 5e-6 * std::cos(a)), 1e-15);
  EXPECT_EQ(link_angle(m, 0, theta_m, 0.0, 0.0, 0.0), theta_m);
  EXPECT_NEAR(link_angle(m, 1, reading_at(m, 1, theta_m), 0.0, 0.0, 0.0), theta_m, 1e-12);
  // Without its periods the cogging's coefficients are no reading model.
  m.cogging_periods = 0.0;
  EXPECT_THROW(check_reading_model(m, "monitor: "), InputError);
}

// reading_at inverts link_angle's harmonics (at rest: no speed, torque or
// flank), with the reducer's errors referenced at home or of mean 0; at home
// the reducer's errors (once per joint, twice per motor revolution) are 0,
// the motor encoder's own (once per motor revolution) is not.
TEST(ReadingModel, ReadingAtInvertsTheHarmonics) {
  ReadingModel m;
  m.gear_ratio = 10.0;
  m.skew_s = {1e-4, 1e-4, 1e-4};  // speed, torque and flank are 0 there: no part of it
  m.harmonic[0] = {2e-4, 0, 0, -1e-4, 0, 0};
  m.harmonic[1] = {0, 3e-5, 0, 0, 1e-5, 0};
  m.harmonic[2] = {1e-4, 0, 5e-5, 0, 0, -8e-5};
  for (const bool at_home : {false, true}) {
    if (at_home) m.reducer_home_rad = {1.1, 3.1, 4.8};
    for (int i = 0; i < 3; ++i)
      for (const double theta : {0.5, 1.7, 4.0}) {
        const double r = reading_at(m, i, theta);
        EXPECT_NEAR(link_angle(m, i, r, 0.0, 0.0, 0.0), theta, 1e-14);
        if (i == 0) {
          EXPECT_GT(std::abs(r - theta), 1e-5);  // joint 1 has errors to take off
        }
      }
  }
  EXPECT_NEAR(reading_at(m, 2, 4.8), 4.8, 1e-15);  // at home joint 3's only error, the reducer's, is 0
  // Joint 1's errors once per joint and twice per motor revolution are both the reducer's: 0 at home.
  EXPECT_NEAR(reading_at(m, 0, 1.1), 1.1, 1e-15);
  // Joint 2's once per motor revolution is its motor encoder's own, of mean 0: not referenced.
  EXPECT_NEAR(link_angle(m, 1, 3.1, 0.0, 0.0, 0.0), 3.1 - (3e-5 * std::sin(31.0) + 1e-5 * std::cos(31.0)), 1e-15);
  EXPECT_TRUE(referenced_at_home(kJointHarmonic) && referenced_at_home(kReducerHarmonic) && !referenced_at_home(1));
}

// Skew and compliance: the same link angles as the calibration's correction
// of its readings (theta_m + s omega - c tau, encoder 1 the reference).
TEST(ReadingModel, LinkAngleAgreesWithTheCalibrationsCorrection) {
  ReadingModel m;
  m.skew_s = {0.0, 5e-5, 1e-4};
  m.compliance_rad_per_Nm = {1e-4, 2e-4, 3e-4};
  const std::vector<Eigen::Vector3d> theta{{0.3, 1.2, -2.0}, {0.31, 1.18, -1.9}};
  const std::vector<Eigen::Vector3d> omega{{0.5, -0.4, 1.1}, {0.0, 2.0, -1.0}};
  const std::vector<Eigen::Vector3d> tau{{1.0, -2.0, 0.5}, {0.2, 0.0, -3.0}};
  const std::vector<Eigen::Vector3d> c = correct_readings(theta, omega, tau, {5e-5, 1e-4, 1e-4, 2e-4, 3e-4});
  for (std::size_t j = 0; j < theta.size(); ++j)
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(link_angle(m, i, theta[j][i], omega[j][i], tau[j][i], 0.0), c[j][i], 1e-15);
}

TEST(ReadingModel, CheckNamesTheValueOutOfRange) {
  EXPECT_NO_THROW(check_reading_model(ReadingModel{}, "m: "));
  const auto message = [](ReadingModel m) {
    try {
      check_reading_model(m, "m: ");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  ReadingModel m;
  m.skew_s[1] = 0.5;
  EXPECT_EQ(message(m), "m: skew_s of encoder 2 must be within +-0.01 s");
  m = ReadingModel{};
  m.clearance_mm[2] = 3.0;
  EXPECT_EQ(message(m), "m: clearance_mm of chain 3 must be in 0..2");
  m = ReadingModel{};
  m.backlash_rad[0] = std::nan("");
  EXPECT_EQ(message(m), "m: cyclic_rad and backlash_rad of joint 1 must be in 0..0.01");
  m = ReadingModel{};
  m.encoder_bits = 0;
  EXPECT_NE(message(m).find("ideal encoder"), std::string::npos);
  m = ReadingModel{};
  m.gear_ratio = 0.5;
  EXPECT_EQ(message(m), "m: gear_ratio must be finite and >= 1");
}

}  // namespace
}  // namespace gpm::calib
