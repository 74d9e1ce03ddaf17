// Tests of hw/safety_supervisor.cpp: no command that breaks a limit reaches
// the backend (randomised), watchdog hold then disable, emergency stop, the
// tracking watch disables the drives when the readings leave the command.
#include <random>

#include <gtest/gtest.h>

#include "hw/hw_errors.hpp"
#include "hw/safety_supervisor.hpp"
#include "hw_test_util.hpp"
#include "models/kinematics.hpp"

namespace gpm::hw {
namespace {

Eigen::Vector3d ik_m(const Robot& r, const Eigen::Vector2d& p) {
  return readings_from_active(r.geometry, inverse_kinematics(r.geometry, p, r.branch).theta_a);
}

struct Rig {
  Robot robot;
  SafetyLimits lim = test::example_limits();
  std::vector<HardwareCommand> rec;
  std::unique_ptr<SafetySupervisor> sup;
  double dt = 0.004;
  Rig() {
    auto backend = std::make_unique<test::RecordingBackend>(ik_m(robot, robot.home), dt);
    backend->record = &rec;
    sup = std::make_unique<SafetySupervisor>(std::move(backend), robot, lim);
    sup->configure();
    sup->read(0.0);
    sup->activate();
  }
};

// Independent check of one forwarded command against the limits, given the
// previous forwarded command and its velocity.
std::string violates(const Robot& robot, const SafetyLimits& L, const HardwareCommand& prev,
                     const Eigen::Vector3d& v_prev, const HardwareCommand& c, double dt,
                     Eigen::Vector3d& v) {
  int n = 0;
  v.setZero();
  for (int i = 0; i < 3; ++i) {
    if (c.mode[i] != JointMode::kPosition) continue;
    ++n;
    const double q = c.theta_m[i];
    if (!(q >= L.joint_min[i] && q <= L.joint_max[i])) return "joint limit";
    const bool was = prev.mode[i] == JointMode::kPosition;
    v[i] = (q - prev.theta_m[i]) / dt;
    if (std::abs(v[i]) > L.max_velocity[i] * (1 + 1e-6)) return "velocity";
    const double a = (v[i] - (was ? v_prev[i] : 0.0)) / dt;
    if (std::abs(a) > L.max_acceleration[i] * (1 + 1e-6) + 1e-6) return "acceleration";
  }
  if (n == 1) return "one joint in position mode";
  if (n < 2) return "";
  Robot r = robot;
  r.limits = {L.reach_margin_mm, L.min_transmission, L.min_direct};
  const Eigen::Vector3d ta = active_from_readings(r.geometry, c.theta_m);
  Eigen::Vector2d p;
  if (n == 3) {
    const auto fk = forward_kinematics(r.geometry, ta);
    if (!fk) return "no fk";
    p = fk->p;
  } else {
    return "";  // two-joint workspace checks are covered by the supervisor's own tests
  }
  if ((p - L.workspace_centre).norm() > L.workspace_radius_mm - L.workspace_margin_mm + 1e-6)
    return "workspace disc";
  const Reach reach = check_reach(r, p);
  if (!reach.ok) return "reach/singularity: " + reach.reason;
  for (int i = 0; i < 3; ++i)
    if (std::abs(wrap_pi(reach.q.theta_a[i] - ta[i])) > L.max_inconsistency_rad + 1e-9)
      return "inconsistent";
  return "";
}

TEST(SafetySupervisor, RandomisedCommandsNeverBreakALimit) {
  Rig rig;
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Vector2d p = rig.robot.home, pv = Eigen::Vector2d::Zero();
  long accepted = 0, rejected = 0;
  double t = 0.0;
  std::array<JointMode, 3> mode{JointMode::kPosition, JointMode::kPosition, JointMode::kPosition};
  for (int k = 0; k < 20000; ++k) {
    t += rig.dt;
    rig.sup->read(t);
    const double r = (u(rng) + 1) / 2;
    HardwareCommand c;
    c.mode = mode;
    if (r < 0.02) {
      // Occasionally change modes, sometimes to an invalid combination.
      for (auto& m : c.mode) m = u(rng) > -0.6 ? JointMode::kPosition : JointMode::kTorqueOff;
      mode = c.mode;
    }
    if (r < 0.05) {
      // A wild jump anywhere.
      c.theta_m = Eigen::Vector3d(1.1, 3.1, 4.8) + 1.5 * Eigen::Vector3d(u(rng), u(rng), u(rng));
    } else if (r < 0.07) {
      c.theta_m = Eigen::Vector3d::Constant(std::nan(""));
    } else if (r < 0.10) {
      continue;  // a missed cycle (the watchdog brakes after 0.1 s)
    } else {
      // A Cartesian random walk, often pushing beyond the workspace edge.
      pv += Eigen::Vector2d(u(rng), u(rng)) * (r > 0.98 ? 20.0 : 1.5);
      pv = pv.cwiseMax(-150).cwiseMin(150);
      p += pv * rig.dt;
      if ((p - rig.robot.home).norm() > 110) p = rig.robot.home + (p - rig.robot.home) * 0.9, pv = -pv;
      try {
        c.theta_m = ik_m(rig.robot, p) + Eigen::Vector3d(u(rng), u(rng), u(rng)) * 2e-5;
      } catch (const InputError&) {
        continue;
      }
    }
    try {
      rig.sup->write(c, t);
      ++accepted;
    } catch (const CommandRejected&) {
      ++rejected;
      // Start the walk again from where the robot is (the supervisor brakes it).
      const auto fk = forward_kinematics(
          rig.robot.geometry, active_from_readings(rig.robot.geometry, rig.sup->last_state().theta_m));
      if (fk) p = fk->p;
      pv.setZero();
      mode = {JointMode::kPosition, JointMode::kPosition, JointMode::kPosition};
    }
  }
  // Replay what reached the backend against the limits, independently.
  HardwareCommand prev = hold_command(ik_m(rig.robot, rig.robot.home));
  Eigen::Vector3d v_prev = Eigen::Vector3d::Zero(), v;
  for (size_t k = 0; k < rig.rec.size(); ++k) {
    const std::string why = violates(rig.robot, rig.lim, prev, v_prev, rig.rec[k], rig.dt, v);
    ASSERT_EQ(why, "") << "forwarded command " << k << " breaks a limit";
    prev = rig.rec[k];
    v_prev = v;
  }
  std::printf("randomised: %ld commands accepted, %ld refused, %zu forwarded (incl. brakes)\n", accepted,
              rejected, rig.rec.size());
  EXPECT_GT(accepted, 5000);
  EXPECT_GT(rejected, 500);
  EXPECT_EQ(rig.sup->rejected_count(), rejected);
  EXPECT_EQ(rig.sup->state(), LifecycleState::kActive);
}

TEST(SafetySupervisor, RefusesCommandsBeyondEachLimit) {
  Rig rig;
  const Eigen::Vector3d home = ik_m(rig.robot, rig.robot.home);
  rig.sup->read(0.004);
  HardwareCommand c = hold_command(home);
  c.theta_m[0] += 0.01;  // 2.5 rad/s in one cycle
  EXPECT_THROW(rig.sup->write(c, 0.004), CommandRejected);
  c = hold_command(home);
  c.theta_m[0] += 0.002;  // 0.5 rad/s from rest: 125 rad/s^2
  EXPECT_THROW(rig.sup->write(c, 0.004), CommandRejected);
  c = hold_command(home);
  c.mode[2] = JointMode::kTorqueOff;
  c.mode[1] = JointMode::kTorqueOff;
  EXPECT_THROW(rig.sup->write(c, 0.004), CommandRejected);  // one joint alone
  c = hold_command(home);
  c.theta_m[2] += 0.00001;  // consistent enough, slow: accepted
  EXPECT_NO_THROW(rig.sup->write(c, 0.004));
  EXPECT_NE(rig.sup->check_pose(ik_m(rig.robot, {216.5 + 88, 250})), "");  // beyond disc - margin
  EXPECT_EQ(rig.sup->check_pose(ik_m(rig.robot, {216.5 + 80, 250})), "");
}

TEST(SafetySupervisor, WatchdogHoldsThenDisables) {
  Rig rig;
  const Eigen::Vector3d home = ik_m(rig.robot, rig.robot.home);
  // Accelerate joint-space along a consistent direction for a while.
  double t = 0.0;
  Eigen::Vector2d p = rig.robot.home;
  for (int k = 1; k <= 50; ++k) {
    t += rig.dt;
    rig.sup->read(t);
    p.x() = rig.robot.home.x() + 0.5 * 40.0 * (k * rig.dt) * (k * rig.dt);  // 40 mm/s^2
    rig.sup->write(hold_command(ik_m(rig.robot, p)), t);
  }
  const size_t sent = rig.rec.size();
  // Silence: after watchdog_hold the supervisor brakes on its own.
  while (t < 0.2 + 0.09) {
    t += rig.dt;
    rig.sup->read(t);
  }
  EXPECT_EQ(rig.rec.size(), sent);  // nothing within 0.09 s
  for (int k = 0; k < 10; ++k) rig.sup->read(t += rig.dt);
  ASSERT_GT(rig.rec.size(), sent);
  EXPECT_TRUE(rig.sup->holding());
  // The brake commands come to rest.
  for (int k = 0; k < 80; ++k) rig.sup->read(t += rig.dt);
  const auto& a = rig.rec[rig.rec.size() - 1].theta_m;
  const auto& b = rig.rec[rig.rec.size() - 2].theta_m;
  EXPECT_LT((a - b).norm(), 1e-12);
  // ... and after watchdog_disable the drives are disabled.
  EXPECT_THROW(
      {
        for (int k = 0; k < 100; ++k) rig.sup->read(t += rig.dt);
      },
      SafetyError);
  EXPECT_EQ(rig.sup->state(), LifecycleState::kError);
  EXPECT_EQ(rig.sup->backend().state(), LifecycleState::kError);
  EXPECT_NE(rig.sup->error_message().find("watchdog"), std::string::npos);
  (void)home;
}

TEST(SafetySupervisor, SlowBackendIsACommsTimeout) {
  Robot robot;
  auto backend = std::make_unique<test::RecordingBackend>(ik_m(robot, robot.home));
  test::RecordingBackend* raw = backend.get();
  raw->wall_clock = true;
  ManualClock clock;  // the backend's reads take the time it is told, no sleeping
  raw->clock = &clock;
  SafetySupervisor sup(std::move(backend), robot, test::example_limits(), clock);
  sup.configure();
  sup.read(0.0);
  sup.activate();
  raw->read_delay_s = 0.09;  // comms_timeout is 0.1 s: in time
  EXPECT_NO_THROW(sup.read(0.004));
  raw->read_delay_s = 0.15;
  try {
    sup.read(0.008);
    FAIL() << "no comms timeout";
  } catch (const SafetyError& e) {
    EXPECT_NE(std::string(e.what()).find("comms timeout: read of recording took"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(sup.state(), LifecycleState::kError);
  EXPECT_EQ(sup.backend().state(), LifecycleState::kError);
}

TEST(SafetySupervisor, EmergencyStopDisablesTheBackend) {
  Rig rig;
  rig.sup->emergency_stop("test");
  EXPECT_EQ(rig.sup->state(), LifecycleState::kError);
  EXPECT_EQ(rig.sup->backend().state(), LifecycleState::kError);
  EXPECT_THROW(rig.sup->write(hold_command(Eigen::Vector3d(1.1, 3.1, 4.8)), 0.0), LifecycleError);
}

// A backend whose joint 1 (torque-off) reads what the mechanism does: here it
// turns away by `drift` rad, as when the five-bar of joints 2 and 3 changes
// assembly mode and the free chain follows the hub elsewhere.
class DriftingBackend final : public RobotHardware {
 public:
  explicit DriftingBackend(const Eigen::Vector3d& start) : position_(start) {}
  double drift = 0.0;
  double period_s() const override { return 0.004; }
  bool simulated_time() const override { return true; }
  std::string describe() const override { return "drifting"; }

 protected:
  void on_configure(HardwareState& s) override { s.theta_m = position_; }
  void on_activate(const HardwareState&) override { enabled_ = true; }
  void on_deactivate() override { enabled_ = false; }
  void on_shutdown() noexcept override { enabled_ = false; }
  void on_error() noexcept override { enabled_ = false; }
  void on_read(double t, HardwareState& s) override {
    s.time_s = t;
    s.theta_m = position_;
    s.theta_m[0] += drift;
    for (auto& d : s.drive) d.enabled = enabled_;
  }
  void on_write(const HardwareCommand& c, double) override {
    for (int i = 0; i < 3; ++i)
      if (c.mode[i] == JointMode::kPosition) position_[i] = c.theta_m[i];
  }

 private:
  Eigen::Vector3d position_;
  bool enabled_ = false;
};

TEST(SafetySupervisor, TrackingWatchDisablesTheDrivesWhenTheReadingsLeaveTheCommand) {
  const Robot robot;
  const Eigen::Vector3d home = ik_m(robot, robot.home);
  auto backend = std::make_unique<DriftingBackend>(home);
  DriftingBackend* raw = backend.get();
  SafetySupervisor sup(std::move(backend), robot, test::example_limits());
  EXPECT_DOUBLE_EQ(sup.limits().max_tracking_mm, 20.0);  // the default of the optional key
  sup.configure();
  sup.read(0.0);
  sup.activate();
  HardwareCommand hold = hold_command(home);
  hold.mode[0] = JointMode::kTorqueOff;
  double t = 0.0;
  double last_ok = 0.0;
  try {
    for (int k = 0; k <= 200; ++k) {
      raw->drift = 0.002 * k;  // up to 0.4 rad
      sup.read(t += 0.004);
      sup.write(hold, t);
      last_ok = raw->drift;
    }
    FAIL() << "no tracking stop";
  } catch (const SafetyError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("tracking: the end-effector from the readings", 0), 0u) << what;
    EXPECT_NE(what.find("(max_tracking 20 mm): drives disabled"), std::string::npos) << what;
  }
  EXPECT_GT(last_ok, 0.01);  // small differences pass
  EXPECT_EQ(sup.state(), LifecycleState::kError);
  EXPECT_EQ(sup.backend().state(), LifecycleState::kError);
}

TEST(SafetySupervisor, RefusesToEnableOutsideTheLimits) {
  Robot robot;
  auto backend = std::make_unique<test::RecordingBackend>(Eigen::Vector3d(0.1, 3.1, 4.8));
  SafetySupervisor sup(std::move(backend), robot, test::example_limits());
  sup.configure();
  EXPECT_THROW(sup.activate(), SafetyError);
  EXPECT_EQ(sup.state(), LifecycleState::kError);
}

}  // namespace
}  // namespace gpm::hw
