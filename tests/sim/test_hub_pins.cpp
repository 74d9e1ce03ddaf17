// Tests of the hub pin offsets in the twin (models/hub_pins.cpp builds the
// MJCF, sim/twin.cpp closes chains 2 and 3 at the pin sites), against
// independent facts:
// - the model compiles and the closed chain assembles: at home the hub
//   centre (site ee) is at robot.home and every link tip on its pin;
// - while the drives move the mechanism the loops stay closed (gap small
//   against the offsets), and the tool point's error against the
//   15-parameter forward kinematics of the true active angles is of the
//   order of the offsets (the hub centre is within max |p_i| of each pin, so
//   the error is at most about 2 max |p_i| plus the FK's own spread), never zero;
// - zero offsets leave the twin exactly as without the key.
#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

#include "models/kinematics.hpp"
#include "sim/sampling.hpp"
#include "sim/trajectory.hpp"
#include "sim/twin.hpp"

namespace gpm::sim {
namespace {

const std::array<std::array<double, 2>, 3> kPins{{{8e-6, -3e-6}, {-5e-6, 12e-6}, {4e-6, 6e-6}}};
constexpr double kLargestPin_m = 13e-6;  // |(-5, 12)| um

TwinConfig pinned() {
  TwinConfig c;
  c.encoder.bits = 0;
  c.effects.mjcf.hub_pin_m = kPins;
  return c;
}

TEST(HubPinsTwin, AssemblesWithTheHubCentreAtHome) {
  const Robot robot;
  const TwinModel m(robot, pinned());
  TwinState s(m, 1);
  EXPECT_LT((s.last.ee_mm - robot.home).norm(), 1e-9);
  EXPECT_LT(s.last.violation_m, 1e-12);
  EXPECT_NE(m.site_pin[1], m.site_ee);
}

struct CircleRun {
  double worst_gap_m = 0.0, worst_err_m = 0.0, least_err_m = 1e9;
};

// Follows a 40 mm circle about home once, drives commanded from the actual
// parameters; the gap and the distance between the tool point and the
// 15-parameter FK of the true active angles.
CircleRun run_circle(const TwinConfig& c) {
  const Robot robot;
  const TwinModel m(robot, c);
  TwinState s(m, 1);
  Session session = make_session(m, s, robot, nullptr);
  const CirclePath circle{robot.home, 40.0, 1.0, 1.0};
  follow_path(session, make_move(session.desired, path_at(circle, 0.0).p, 100.0));
  const double period = m.timestep_s() * m.steps_per_tick();
  CircleRun r;
  for (double t = 0.0; t < 1.0; t += period) {
    const TwinSnapshot snap = advance(session, path_at(circle, t));
    r.worst_gap_m = std::max(r.worst_gap_m, snap.violation_m);
    const auto fk = forward_kinematics(robot.geometry, snap.theta_a);
    if (!fk) throw std::runtime_error("FK failed");
    const double err_m = (fk->p - snap.ee_mm).norm() * 1e-3;
    r.worst_err_m = std::max(r.worst_err_m, err_m), r.least_err_m = std::min(r.least_err_m, err_m);
  }
  return r;
}

TEST(HubPinsTwin, LoopsStayClosedAndTheToolPointMissesTheFifteenParameterModelByTheOffsetsOrder) {
  TwinConfig ideal;
  ideal.encoder.bits = 0;
  const CircleRun base = run_circle(ideal), pins = run_circle(pinned());
  RecordProperty("gap_m", std::to_string(pins.worst_gap_m) + " (ideal " + std::to_string(base.worst_gap_m) + ")");
  RecordProperty("fk_error_m", std::to_string(pins.least_err_m) + " .. " + std::to_string(pins.worst_err_m));
  // The ideal twin's own gap on this path (its constraint softness under motion) is the reference.
  EXPECT_LT(pins.worst_gap_m, base.worst_gap_m + 0.01 * kLargestPin_m) << "the pins open the loops no further";
  EXPECT_LT(base.worst_err_m, 2.0 * base.worst_gap_m + 1e-9) << "without pins the FK holds the tool point to the loops' own gap";
  EXPECT_LT(pins.worst_err_m, 4.0 * kLargestPin_m) << "of the order of the offsets";
  EXPECT_GT(pins.least_err_m, 0.1 * kLargestPin_m) << "the 15 parameters cannot hold the offsets";
}

TEST(HubPinsTwin, ZeroOffsetsStepExactlyAsWithoutTheKey) {
  const Robot robot;
  TwinConfig plain;
  TwinConfig zero = plain;
  zero.effects.mjcf.hub_pin_m = {};
  const TwinModel a(robot, plain), b(robot, zero);
  EXPECT_EQ(a.xml(), b.xml());
  TwinState sa(a, 3), sb(b, 3);
  const Eigen::Vector3d cmd = sa.last.readings + Eigen::Vector3d(0.01, -0.005, 0.0);
  twin_command(sa, cmd, Eigen::Vector3d::Zero());
  twin_command(sb, cmd, Eigen::Vector3d::Zero());
  for (int k = 0; k < 200; ++k) twin_step(a, sa), twin_step(b, sb);
  EXPECT_EQ(sa.last.readings, sb.last.readings);
  EXPECT_EQ(sa.last.ee_mm, sb.last.ee_mm);
}

}  // namespace
}  // namespace gpm::sim
