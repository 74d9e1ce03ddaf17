// Tests of hw/procedures/trajectory_session.cpp: a path sampled on the fly
// through the hardware interface records one sample per `every` cycles with
// the bookkeeping of the twin's sim::sample_along (the torque read with the
// readings, the cycle's before, the mean since the sample before), each
// joint's read time, the commanded point; the twin backend follows the path
// and its samples read back as a file taken on the fly; a path outside the
// limits, drives that report no torque and a partly recorded file are
// refused before anything moves; a finished file is kept and nothing moves;
// a robot that leaves its plan ends the path early and retraces it; a
// planned stage samples the path's first seconds and retraces them.
#include <gtest/gtest.h>

#include <cmath>

#include "hw/hardware_config.hpp"
#include "hw/procedures/trajectory_session.hpp"
#include "hw/safety_supervisor.hpp"
#include "hw_test_util.hpp"
#include "models/errors.hpp"
#include "models/kinematics.hpp"
#include "models/samples.hpp"
#include "sim/waypoint_path.hpp"

namespace gpm::hw {
namespace {

const std::string kSrc = GPM_SOURCE_DIR;

Eigen::Vector3d ik_m(const Robot& r, const Eigen::Vector2d& p) {
  return readings_from_active(r.geometry, inverse_kinematics(r.geometry, p, r.branch).theta_a);
}

// A short excitation path from home through three poses, slow enough for the example limits.
TrajectoryPlan small_plan(int every) {
  TrajectoryPlan plan;
  const Robot robot;
  sim::WaypointLimits lim;
  lim.max_speed_mm_s = 40;
  lim.max_accel_mm_s2 = 200;
  lim.max_normal_mm_s2 = 200;
  plan.path = sim::excitation_path(robot.home, {{236.5, 260}, {206.5, 240}, {226.5, 230}}, lim);
  plan.every = every;
  plan.settle = {0.01, 0.0, 1.0};
  return plan;
}

struct Rig {
  Robot robot;
  std::vector<HardwareCommand> rec;
  test::RecordingBackend* backend = nullptr;
  std::unique_ptr<SafetySupervisor> sup;
  explicit Rig(bool torque = true, const SafetyLimits& lim = test::example_limits()) {
    auto b = std::make_unique<test::RecordingBackend>(ik_m(robot, robot.home), 0.004);
    b->record = &rec;
    b->count_torque = torque;
    b->read_offset_s = {0.0, 0.0005, 0.001};
    backend = b.get();
    sup = std::make_unique<SafetySupervisor>(std::move(b), robot, lim);
  }
};

TEST(TrajectorySession, RecordsTheTorqueHistoryAndReadTimesOfEverySample) {
  test::TempDir dir("traj_history");
  const TrajectoryPlan plan = small_plan(3);
  Rig rig;
  const std::string path = (dir / "s.csv").string();
  {
    SampleLog log(path, false, SampleColumns::kOnTheFly);
    const SessionResult r = run_trajectory_session(*rig.sup, plan, log, nullptr);
    EXPECT_EQ(r.taken, trajectory_sample_count(plan, 0.004));
  }
  const Samples s = read_samples_csv(path);
  ASSERT_EQ(static_cast<long>(s.size()), trajectory_sample_count(plan, 0.004));
  ASSERT_EQ(s.t.size(), s.size());
  ASSERT_EQ(s.t_read.size(), s.size());
  // The readings are the commands (the backend follows exactly): the
  // controller's IK of the sample's point, one cycle late (read before the command).
  const std::vector<Eigen::Vector3d> q = trajectory_commands(rig.robot, plan, 0.004);
  // Read count r at sample j: the reads before the path, then one per cycle.
  const double r0 = s.tau[0][0];
  for (std::size_t j = 1; j < s.size(); ++j) {
    EXPECT_NEAR(s.t[j] - s.t[j - 1], 3 * 0.004, 1e-12) << j;
    const double r = r0 + 3.0 * static_cast<double>(j);
    for (int i = 0; i < 3; ++i) {
      EXPECT_DOUBLE_EQ(s.tau[j][i], r * (i + 1)) << j;
      EXPECT_DOUBLE_EQ(s.tau_last[j][i], (r - 1) * (i + 1)) << j;
      // Mean of the reads since the sample before (it included): r-3, r-2, r-1.
      EXPECT_DOUBLE_EQ(s.tau_between[j][i], (r - 2) * (i + 1)) << j;
    }
    EXPECT_NEAR(s.t_read[j][1] - s.t[j], 0.0005, 1e-9);
    EXPECT_NEAR(s.t_read[j][2] - s.t[j], 0.001, 1e-9);
    EXPECT_NEAR((s.theta_m[j] - q[3 * j - 1]).norm(), 0.0, 1e-12) << j;
  }
  EXPECT_DOUBLE_EQ(s.t[0], 0.0);
}

TEST(TrajectorySession, TheTwinFollowsThePathAndItsFileReadsAsTakenOnTheFly) {
  test::TempDir dir("traj_twin");
  test::write_text(dir / "hw.yaml", "backend: twin\nrate_hz: 250\ncontroller: " + kSrc +
                                        "/models/gpm2002.yaml\ntwin: {scenario: " + kSrc +
                                        "/tests/fixtures/twin_disc.yaml}\n" + test::kSafetyYaml);
  const HardwareConfig cfg = load_hardware_config((dir / "hw.yaml").string());
  auto hw = make_hardware(cfg);
  const TrajectoryPlan plan = small_plan(1);
  const std::string path = (dir / "s.csv").string();
  {
    SampleLog log(path, false, SampleColumns::kOnTheFly);
    run_trajectory_session(*hw, plan, log, nullptr);
  }
  const Samples s = read_samples_csv(path);
  ASSERT_EQ(static_cast<long>(s.size()), trajectory_sample_count(plan, 0.004));
  // Where the readings put the end-effector (nominal model) against the
  // commanded point: the actual robot is 0.3 mm off nominal and the drives lag a little.
  const Robot nominal;
  double worst = 0.0, torque = 0.0;
  for (std::size_t j = 0; j < s.size(); ++j) {
    const auto fk = forward_kinematics(nominal.geometry, active_from_readings(nominal.geometry, s.theta_m[j]));
    ASSERT_TRUE(fk.has_value());
    Eigen::Vector2d p, v;
    sim::waypoint_at(plan.path, s.t[j], p, v);
    worst = std::max(worst, (fk->p - p).norm());
    torque = std::max(torque, s.tau[j].cwiseAbs().maxCoeff());
    // The twin latches its encoders at one instant, its last drive tick
    // (2 kHz), at most one drive period before the cycle's time.
    EXPECT_EQ(s.t_read[j], Eigen::Vector3d::Constant(s.t_read[j][0]));
    EXPECT_GE(s.t[j] - s.t_read[j][0], -1e-9);
    EXPECT_LE(s.t[j] - s.t_read[j][0], 0.0005 + 1e-9);
  }
  EXPECT_LT(worst, 3.0);
  EXPECT_GT(torque, 0.0);  // the twin reports its drive torques
}

// Joint 1 torque-off on a backend that moves only its position joints: its
// reading stays where it was, so the end-effector from the three readings
// leaves the commanded point more and more along the path. Past
// retreat_fraction of the watch's bound the path ends: the samples taken are
// kept, the robot slows along the path and retraces it to the start (every
// command accepted by the supervisor), and the error says so; without the
// retreat the watch itself disables the drives at its bound, off the path.
TEST(TrajectorySession, ARobotLeavingItsPlanEndsThePathAndRetracesIt) {
  SafetyLimits lim = test::example_limits();
  TrajectoryPlan plan = small_plan(1);
  plan.modes = {JointMode::kTorqueOff, JointMode::kPosition, JointMode::kPosition};
  // Where the frozen reading puts the readings' end-effector at the path's far end.
  Rig probe;
  const std::vector<Eigen::Vector3d> q = trajectory_commands(probe.robot, plan, 0.004);
  double far_mm = 0.0;
  for (const Eigen::Vector3d& qk : q) {
    const Eigen::Vector3d reading(q[0][0], qk[1], qk[2]);
    const auto fk = forward_kinematics(probe.robot.geometry, active_from_readings(probe.robot.geometry, reading));
    const auto cmd = forward_kinematics(probe.robot.geometry, active_from_readings(probe.robot.geometry, qk));
    if (fk && cmd) far_mm = std::max(far_mm, (fk->p - cmd->p).norm());
  }
  ASSERT_GT(far_mm, 1.0);
  lim.max_tracking_mm = far_mm;  // the retreat (0.7 of it) comes first; the watch would trip further on
  for (const bool retreat : {true, false}) {
    test::TempDir dir("traj_retreat");
    plan.retreat_fraction = retreat ? 0.7 : 0.0;
    lim.max_tracking_mm = retreat ? far_mm : 0.5 * far_mm;
    Rig rig(true, lim);
    const std::string path = (dir / "s.csv").string();
    try {
      SampleLog log(path, false, SampleColumns::kOnTheFly);
      run_trajectory_session(*rig.sup, plan, log, nullptr);
      ADD_FAILURE() << "the path ran to its end";
    } catch (const HardwareError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.find("retraced its path to the start") != std::string::npos, retreat) << what;
      EXPECT_NE(what.find("samples kept in " + path), std::string::npos) << what;
    }
    const long kept = static_cast<long>(read_samples_csv(path).size());
    EXPECT_GT(kept, 10);
    EXPECT_LT(kept, trajectory_sample_count(plan, 0.004));
    // Retraced: the last command is the path's start, at rest (the two last equal to rounding).
    ASSERT_GE(rig.rec.size(), 2u);
    const Eigen::Vector3d last = rig.rec.back().theta_m, before = rig.rec[rig.rec.size() - 2].theta_m;
    for (int i = 1; i < 3; ++i) {
      if (retreat) {
        EXPECT_NEAR(last[i], q[0][i] + std::round((last[i] - q[0][i]) / (2 * M_PI)) * 2 * M_PI, 1e-9) << i;
        EXPECT_NEAR(last[i], before[i], 1e-6) << i;
      }
    }
    EXPECT_EQ(rig.sup->rejected_count(), 0);
  }
}

// A planned first stage (end_s): the samples up to end_s and no more, each
// the whole path's sample of its id; the robot slows and retraces them to the
// path's start, and the session ends normally.
TEST(TrajectorySession, AStageSamplesThePathsFirstSecondsAndRetracesThem) {
  test::TempDir dir("traj_stage");
  TrajectoryPlan whole = small_plan(2);
  TrajectoryPlan stage = whole;
  stage.end_s = 0.3 * sim::waypoint_duration(whole.path);
  const long n = trajectory_sample_count(stage, 0.004);
  EXPECT_EQ(n, std::lround(stage.end_s / 0.004) / 2 + 1);
  EXPECT_LT(n, trajectory_sample_count(whole, 0.004));
  Rig rig;
  const std::string path = (dir / "s.csv").string();
  {
    SampleLog log(path, false, SampleColumns::kOnTheFly);
    const SessionResult r = run_trajectory_session(*rig.sup, stage, log, nullptr);
    EXPECT_EQ(r.taken, n);
    // Moving to the start, the stage, and back along it: longer than the stage twice.
    EXPECT_GT(r.duration_s, 2.0 * stage.end_s);
  }
  const Samples s = read_samples_csv(path);
  ASSERT_EQ(static_cast<long>(s.size()), n);
  const std::vector<Eigen::Vector3d> q = trajectory_commands(rig.robot, whole, 0.004);
  for (std::size_t j = 1; j < s.size(); ++j) EXPECT_NEAR((s.theta_m[j] - q[2 * j - 1]).norm(), 0.0, 1e-12) << j;
  const Eigen::Vector3d last = rig.rec.back().theta_m;
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(last[i], q[0][i] + std::round((last[i] - q[0][i]) / (2 * M_PI)) * 2 * M_PI, 1e-9) << i;
  EXPECT_EQ(rig.sup->rejected_count(), 0);
  // A resumed stage whose file holds its samples moves nothing.
  SampleLog again(path, true, SampleColumns::kOnTheFly);
  Rig idle;
  EXPECT_EQ(run_trajectory_session(*idle.sup, stage, again, nullptr).skipped, n);
  EXPECT_TRUE(idle.rec.empty());
}

TEST(TrajectorySession, APathOutsideTheLimitsIsRefusedBeforeAnythingMoves) {
  test::TempDir dir("traj_limits");
  SafetyLimits lim = test::example_limits();
  lim.max_velocity = {0.05, 0.05, 0.05};
  Rig rig(true, lim);
  SampleLog log((dir / "s.csv").string(), false, SampleColumns::kOnTheFly);
  try {
    run_trajectory_session(*rig.sup, small_plan(1), log, nullptr);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("max_velocity"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(rig.rec.empty());
  EXPECT_EQ(log.size(), 0u);
  log.close_and_discard_if_empty();  // as the command does on its way out
  EXPECT_FALSE(std::filesystem::exists(dir / "s.csv"));
}

TEST(TrajectorySession, DrivesThatReportNoTorqueAreRefusedBeforeAnythingMoves) {
  test::TempDir dir("traj_torque");
  Rig rig(false);
  SampleLog log((dir / "s.csv").string(), false, SampleColumns::kOnTheFly);
  try {
    run_trajectory_session(*rig.sup, small_plan(1), log, nullptr);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("torque"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(rig.rec.empty());
}

TEST(TrajectorySession, AFinishedFileIsKeptAndAPartOfOneRefused) {
  test::TempDir dir("traj_resume");
  const TrajectoryPlan plan = small_plan(2);
  const std::string path = (dir / "s.csv").string();
  {
    Rig rig;
    SampleLog log(path, false, SampleColumns::kOnTheFly);
    run_trajectory_session(*rig.sup, plan, log, nullptr);
  }
  const std::string full = test::read_text(path);
  {  // finished: nothing moves, the file stays as it was
    Rig rig;
    SampleLog log(path, true, SampleColumns::kOnTheFly);
    const SessionResult r = run_trajectory_session(*rig.sup, plan, log, nullptr);
    EXPECT_EQ(r.taken, 0);
    EXPECT_EQ(r.skipped, trajectory_sample_count(plan, 0.004));
    EXPECT_TRUE(rig.rec.empty());
  }
  EXPECT_EQ(test::read_text(path), full);
  // The first half of it: refused, nothing moves, the file unchanged.
  std::string half = full.substr(0, full.find('\n', full.size() / 2) + 1);
  test::write_text(path, half);
  Rig rig;
  SampleLog log(path, true, SampleColumns::kOnTheFly);
  EXPECT_THROW(run_trajectory_session(*rig.sup, plan, log, nullptr), InputError);
  EXPECT_TRUE(rig.rec.empty());
  EXPECT_EQ(test::read_text(path), half);
}

TEST(TrajectorySession, AFileOfSamplesAtRestIsNotContinuedOnTheFly) {
  test::TempDir dir("traj_columns");
  const std::string path = (dir / "s.csv").string();
  {
    SampleLog log(path, false, SampleColumns::kAtRest);
    log.append(0, Eigen::Vector3d(1.1, 3.1, 4.8), Eigen::Vector2d(216.5, 250));
  }
  EXPECT_THROW(SampleLog(path, true, SampleColumns::kOnTheFly), InputError);
}

}  // namespace
}  // namespace gpm::hw
