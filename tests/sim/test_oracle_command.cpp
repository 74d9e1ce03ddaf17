// Tests of sim/oracle_command.cpp: the floor's commands.
// - without reading effects they are the plain commands theta_a - dth;
// - the readings it gives satisfy its defining equations, written out here
//   (the motor angle by bisection, the encoder's error by its formula);
// - on the twin, three drives holding them put the links at the target up
//   to Hooke's twist of the torque they hold, where the plain commands leave
//   the transmission and encoder errors.
#include "sim/oracle_command.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "models/kinematics.hpp"
#include "sim/twin.hpp"

namespace gpm::sim {
namespace {

constexpr double kCompliance = 1e-4;  // rad/N m

// 4 kHz drive loop and 0.25 ms steps, ideal encoders; with reducers
// (N = 10), their transmission errors and an encoder error once per motor revolution.
TwinConfig reading_errors_config(bool errors) {
  TwinConfig c;
  c.mjcf.timestep_s = 0.00025;
  c.mjcf.solref_timeconst_s = 0.0005;
  c.servo_rate_hz = 4000.0;
  c.encoder.bits = 0;
  c.effects.gear_ratio = 10.0;
  c.effects.mjcf.compliance_rad_per_Nm.fill(kCompliance);
  if (!errors) return c;
  for (std::size_t k = 0; k < 3; ++k) {
    DriveChain& d = c.effects.drive.chain[k];
    d.te_joint_rad = 4e-4, d.te_joint_phase_rad = 0.4 + static_cast<double>(k);
    d.te_motor_rad = 1e-4, d.te_motor_phase_rad = 2.0;
    c.effects.encoder_cyclic_rad[k] = 5e-5, c.effects.encoder_phase_rad[k] = 1.0 - static_cast<double>(k);
  }
  return c;
}

// The link angles at p (mm) of robot's actual geometry.
Eigen::Vector3d links_at(const Robot& r, const Eigen::Vector2d& p) {
  return inverse_kinematics(r.geometry, p, r.branch).theta_a;
}

Eigen::Vector3d offsets(const Robot& r) { return {r.geometry.dth_(0), r.geometry.dth_(1), r.geometry.dth_(2)}; }

TEST(OracleCommand, WithoutReadingErrorsThePlainCommands) {
  const Robot robot;
  const TwinModel m(robot, reading_errors_config(false));
  const Eigen::Vector3d theta_a = links_at(robot, robot.home + Eigen::Vector2d(25.0, -40.0));
  const Eigen::Vector3d r = oracle_readings(m, theta_a, offsets(robot));
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(r[i], wrap_2pi(theta_a[i] - robot.geometry.dth_(i)), 1e-15);
}

TEST(OracleCommand, ReadingsSolveTheirDefiningEquations) {
  const Robot robot;
  const TwinConfig c = reading_errors_config(true);
  const TwinModel m(robot, c);
  TwinState s(m, 1);
  const Eigen::Vector3d theta_m0 = s.last.theta_motor;
  const Eigen::Vector3d theta_a = links_at(robot, robot.home + Eigen::Vector2d(25.0, -40.0));
  const Eigen::Vector3d r = oracle_readings(m, theta_a, offsets(robot));
  for (std::size_t k = 0; k < 3; ++k) {
    const DriveChain& d = c.effects.drive.chain[k];
    const auto te = [&](double x) {
      return d.te_joint_rad * std::sin(x + d.te_joint_phase_rad) + d.te_motor_rad * std::sin(2 * 10.0 * x + d.te_motor_phase_rad);
    };
    const auto i = static_cast<long>(k);
    // theta_m - TE(theta_m) + TE(theta_m0) = theta_a by bisection (the left side rises in theta_m).
    double lo = theta_a[i] - 1e-2, hi = theta_a[i] + 1e-2;
    for (int n = 0; n < 100; ++n) {
      const double mid = 0.5 * (lo + hi);
      (mid - te(mid) + te(theta_m0[i]) < theta_a[i] ? lo : hi) = mid;
    }
    const double reading = lo - robot.geometry.dth_(static_cast<int>(k));
    const double encoder = 5e-5 * std::sin(10.0 * reading + c.effects.encoder_phase_rad[k]);
    EXPECT_NEAR(r[i], wrap_2pi(reading + encoder), 1e-12) << "chain " << k + 1;
    EXPECT_GT(std::abs(r[i] - wrap_2pi(theta_a[i] - robot.geometry.dth_(static_cast<int>(k)))), 1e-5);  // something to check
  }
}

// The links' distance (rad, largest over the chains) from the target, less
// Hooke's twist of the torque each drive holds, after the drives have held
// readings for 1.5 s.
double link_error_beyond_twist(const TwinModel& m, const Eigen::Vector3d& readings, const Eigen::Vector3d& target) {
  TwinState s(m, 1);
  twin_command(s, readings, Eigen::Vector3d::Zero());
  const long n = std::lround(1.5 / m.timestep_s());
  for (long k = 0; k < n; ++k) twin_step(m, s);
  twin_sense(m, s);
  double worst = 0.0;
  for (long i = 0; i < 3; ++i)
    worst = std::max(worst, std::abs(s.last.theta_a[i] - target[i]) - kCompliance * std::abs(s.last.torque[i]));
  return worst;
}

TEST(OracleCommand, TheTwinsLinksStandAtTheTarget) {
  const Robot robot;
  const TwinModel m(robot, reading_errors_config(true));
  const Eigen::Vector3d target = links_at(robot, robot.home + Eigen::Vector2d(25.0, -40.0));
  Eigen::Vector3d plain;
  for (int i = 0; i < 3; ++i) plain[i] = wrap_2pi(target[i] - robot.geometry.dth_(i));
  EXPECT_LT(link_error_beyond_twist(m, oracle_readings(m, target, offsets(robot)), target), 1e-7);
  EXPECT_GT(link_error_beyond_twist(m, plain, target), 1e-4);  // the errors the oracle knows
}

}  // namespace
}  // namespace gpm::sim
