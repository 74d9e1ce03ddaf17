// Tests of hw/procedures/sampling_session.cpp (with the drive emulator, the Modbus
// transport and the drive backend underneath): the same session on `twin` and
// on `modbus` gives samples within one encoder count; injected emulator faults
// end in one clear error, drives disabled, samples so far intact on disk;
// a resumed session skips what is recorded; averaging along the dither figure
// brings the readings far closer to a closed loop of the actual mechanism
// than holding still, and adds no error of its own.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "hw/backends/drive_emulator.hpp"
#include "hw/clock.hpp"
#include "hw/hardware_config.hpp"
#include "hw/hw_errors.hpp"
#include "hw/procedures/sampling_session.hpp"
#include "hw/safety_supervisor.hpp"
#include "hw_test_util.hpp"
#include "calib/residuals.hpp"
#include "hw/procedures/motion.hpp"  // motion_profile
#include "models/errors.hpp"
#include "models/kinematics.hpp"
#include "models/samples.hpp"

namespace gpm::hw {
namespace {

namespace fs = std::filesystem;
const std::string kSrc = GPM_SOURCE_DIR;
// The example disc scenario: a perturbed actual robot, 17-bit encoders.
const std::string kScenario = kSrc + "/tests/fixtures/twin_disc.yaml";
const double kCount = 2 * M_PI / 131072;

SessionPlan plan() {
  SessionPlan p;
  p.poses = {{236.5, 260}, {196.5, 240}, {230, 225}, {205, 270}};
  p.options.move_speed_mm_s = 150;
  p.options.settle = {0.001, 0.2, 3.0};
  p.options.average_s = 0.1;
  return p;
}

std::string hw_yaml(const std::string& backend, const std::string& extra) {
  return "backend: " + backend + "\nrate_hz: 250\ncontroller: " + kSrc +
         "/models/gpm2002.yaml\n" + extra + test::kSafetyYaml;
}

// Writes the emulator's register map with the given port; returns its path.
fs::path map_file(const fs::path& dir, int port) {
  std::string text = test::read_text(kSrc + "/hw/examples/register_map_emulator.yaml");
  text.replace(text.find("port: 1502"), 10, "port: " + std::to_string(port));
  const fs::path p = dir / "map.yaml";
  test::write_text(p, text);
  return p;
}

struct ModbusRig {
  test::TempDir dir;
  // One stepped clock for the client and the emulator: it moves only when the
  // client waits for its next cycle (or the emulator delays or stalls), so
  // every reply depends on the clock and the requests, not on the load.
  ManualClock clock;
  std::unique_ptr<DriveEmulator> emu;
  HardwareConfig config;
  explicit ModbusRig(const std::string& name, const EmulatorFaults& faults = {}) : dir(name) {
    EmulatorOptions o;
    o.faults = faults;
    o.clock = &clock;
    const RegisterMap map0 = load_register_map(map_file(dir, 1502).string());
    emu = std::make_unique<DriveEmulator>(map0, twin_config_from_scenario(kScenario, 0.004), o);
    const int port = emu->start();
    map_file(dir, port);
    test::write_text(dir / "hw.yaml", hw_yaml("modbus", "modbus: {register_map: map.yaml}\n"));
    config = load_hardware_config((dir / "hw.yaml").string());
  }
};

Samples run_twin(const fs::path& dir) {
  test::write_text(dir / "twin.yaml", hw_yaml("twin", "twin: {scenario: " + kScenario + "}\n"));
  const HardwareConfig c = load_hardware_config((dir / "twin.yaml").string());
  auto hw = make_hardware(c);
  SampleLog log((dir / "twin.csv").string(), false);
  const SessionResult r = run_sampling_session(*hw, plan(), log);
  EXPECT_EQ(r.taken, 4);
  return read_samples_csv((dir / "twin.csv").string());
}

TEST(SamplingSession, TwinAndModbusAgreeWithinOneCount) {
  ModbusRig rig("parity");
  const Samples twin = run_twin(rig.dir);
  auto hw = make_hardware(rig.config, rig.clock);
  SampleLog log((rig.dir / "modbus.csv").string(), false);
  const SessionResult r = run_sampling_session(*hw, plan(), log);
  EXPECT_EQ(r.taken, 4);
  const Samples mb = read_samples_csv((rig.dir / "modbus.csv").string());
  ASSERT_EQ(mb.size(), 4u);
  ASSERT_EQ(twin.size(), 4u);
  double worst = 0.0;
  for (size_t k = 0; k < 4; ++k)
    for (int i = 0; i < 3; ++i) {
      const double d = std::abs(mb.theta_m[k][i] - twin.theta_m[k][i]);
      worst = std::max(worst, d);
    }
  EXPECT_LE(worst, kCount * 1.0001) << "worst difference " << worst / kCount << " counts";
  std::printf("twin vs modbus: worst difference %.3f encoder counts\n", worst / kCount);
  EXPECT_EQ(hw->state(), LifecycleState::kFinalized);
  rig.emu->tick_now();  // the client's disable is in the control words: off at the next tick
  EXPECT_EQ(rig.emu->power_on(), (std::array<bool, 3>{false, false, false}));
}

// Runs the session against an emulator with faults; expects one HardwareError,
// the drives off, and the samples before the fault on disk.
void expect_fault_handled(const std::string& name, const EmulatorFaults& f, const std::string& words,
                          bool client_disables) {
  ModbusRig rig(name, f);
  auto hw = make_hardware(rig.config, rig.clock);
  const fs::path csv = rig.dir / "s.csv";
  std::string message;
  {
    SampleLog log(csv.string(), false);
    try {
      run_sampling_session(*hw, plan(), log);
    } catch (const HardwareError& e) {
      message = e.what();
    }
  }
  EXPECT_NE(message, "") << name << ": no error";
  EXPECT_NE(message.find(words), std::string::npos) << message;
  EXPECT_NE(message.find("samples kept"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos);
  // Drives disabled: by the client (at the next tick), or, with the connection
  // gone or stalled, by the drives' own comms watchdog (the clock moves past
  // it once the client is gone and every request it sent was served).
  hw.reset();
  ASSERT_TRUE(rig.emu->wait_until_no_clients(30.0)) << name;
  if (!client_disables) rig.clock.advance(1.0);
  rig.emu->tick_now();
  EXPECT_EQ(rig.emu->power_on(), (std::array<bool, 3>{false, false, false})) << name;
  const Samples s = read_samples_csv(csv.string());
  EXPECT_GE(s.size(), 1u) << name;
  EXPECT_LT(s.size(), 4u) << name;
  std::printf("%s: %zu samples kept; error: %s\n", name.c_str(), s.size(), message.c_str());
}

// Four writes a cycle (three position commands, the latch): 1500 writes fall
// after the first sample (move, settle, dither figure) and before the second.
constexpr long kAfterFirstSample = 1500;

TEST(SamplingSession, FaultConnectionDropped) {
  EmulatorFaults f;
  f.drop_after_writes = kAfterFirstSample;
  expect_fault_handled("drop", f, "modbus-tcp 127.0.0.1", false);
}

TEST(SamplingSession, FaultDelayedReplies) {
  EmulatorFaults f;
  f.delay_after_writes = kAfterFirstSample;
  f.delay_s = 0.2;
  expect_fault_handled("delay", f, "127.0.0.1", false);
}

TEST(SamplingSession, FaultBitSet) {
  EmulatorFaults f;
  f.fault_after_writes = kAfterFirstSample;
  f.fault_axis = 1;
  expect_fault_handled("fault", f, "drive 2 reports a fault (fault code 0x2310", true);
}

TEST(SamplingSession, FaultGarbageRegisters) {
  EmulatorFaults f;
  f.garbage_after_writes = kAfterFirstSample;
  f.garbage_axis = 2;
  expect_fault_handled("garbage", f, "drive 3: implausible encoder reading", true);
}

TEST(SamplingSession, ResumeSkipsRecordedPoses) {
  const test::TempDir dir("resume");
  test::write_text(dir / "twin.yaml", hw_yaml("twin", "twin: {scenario: " + kScenario + "}\n"));
  const HardwareConfig c = load_hardware_config((dir / "twin.yaml").string());
  SessionPlan p = plan();
  p.poses.resize(2);
  {
    auto hw = make_hardware(c);
    SampleLog log((dir / "s.csv").string(), false);
    EXPECT_EQ(run_sampling_session(*hw, p, log).taken, 2);
  }
  const std::string first = test::read_text(dir / "s.csv");
  p = plan();
  auto hw = make_hardware(c);
  SampleLog log((dir / "s.csv").string(), true);
  const SessionResult r = run_sampling_session(*hw, p, log);
  EXPECT_EQ(r.skipped, 2);
  EXPECT_EQ(r.taken, 2);
  const std::string all = test::read_text(dir / "s.csv");
  EXPECT_EQ(all.substr(0, first.size()), first);
  EXPECT_EQ(read_samples_csv((dir / "s.csv").string()).size(), 4u);
}

TEST(SamplingSession, PoseOutsideTheLimitsIsRefusedBeforeMoving) {
  const test::TempDir dir("outside");
  test::write_text(dir / "twin.yaml", hw_yaml("twin", "twin: {scenario: " + kScenario + "}\n"));
  auto hw = make_hardware(load_hardware_config((dir / "twin.yaml").string()));
  SessionPlan p = plan();
  p.poses.push_back({216.5 + 100, 250});
  SampleLog log((dir / "s.csv").string(), false);
  EXPECT_THROW(run_sampling_session(*hw, p, log), InputError);
  EXPECT_EQ(hw->state(), LifecycleState::kUnconfigured);
}

// Drives that never move (e.g. the emulator given a NaN command period):
// readings that do not change while the joints are commanded to move fail
// the session (HardwareError, drives disabled) instead of being recorded.
TEST(SamplingSession, ReadingsThatNeverChangeFailTheSession) {
  const test::TempDir dir("frozen");
  const Robot robot;
  const Eigen::Vector3d home =
      readings_from_active(robot.geometry, inverse_kinematics(robot.geometry, robot.home, robot.branch).theta_a);
  auto backend = std::make_unique<test::RecordingBackend>(home);
  backend->frozen = true;
  // The tracking watch would stop it too (20 mm off the plan); widened here
  // so that this test sees the followed-command check on its own.
  SafetyLimits limits = test::example_limits();
  limits.max_tracking_mm = 1000.0;
  SafetySupervisor hw(std::move(backend), robot, limits);
  SessionPlan p = plan();
  p.options.settle = {0.001, 0.02, 1.0};
  SampleLog log((dir / "s.csv").string(), false);
  try {
    run_sampling_session(hw, p, log);
    ADD_FAILURE() << "a session whose readings never changed succeeded";
  } catch (const InputError& e) {
    ADD_FAILURE() << e.what();
  } catch (const HardwareError& e) {
    EXPECT_NE(std::string(e.what()).find("sample 0: joint"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("did not follow its command"), std::string::npos) << e.what();
  }
  EXPECT_EQ(log.size(), 0u);
  log.close_and_discard_if_empty();  // as gpm sample does: the log made at once holds no sample
  EXPECT_FALSE(fs::exists(dir / "s.csv"));
}

// Resume checks the recorded plan: another plan (poses, order) or another
// robot is refused before anything moves; the file is untouched.
TEST(SamplingSession, ResumeRefusesAnotherPlanOrRobot) {
  const test::TempDir dir("resume_plan");
  test::write_text(dir / "twin.yaml", hw_yaml("twin", "twin: {scenario: " + kScenario + "}\n"));
  const HardwareConfig c = load_hardware_config((dir / "twin.yaml").string());
  SessionPlan p = plan();
  p.poses.resize(2);
  {
    auto hw = make_hardware(c);
    SampleLog log((dir / "s.csv").string(), false);
    EXPECT_EQ(run_sampling_session(*hw, p, log).taken, 2);
  }
  const std::string recorded = test::read_text(dir / "s.csv");
  auto resume_error = [&](const SessionPlan& q) {
    auto hw = make_hardware(c);
    SampleLog log((dir / "s.csv").string(), true);
    try {
      run_sampling_session(*hw, q, log);
    } catch (const InputError& e) {
      EXPECT_EQ(hw->state(), LifecycleState::kUnconfigured);  // nothing moved
      return std::string(e.what());
    }
    return std::string();
  };
  SessionPlan swapped = plan();
  std::swap(swapped.poses[0], swapped.poses[1]);
  EXPECT_NE(resume_error(swapped).find("recorded with another plan"), std::string::npos);
  SessionPlan shorter = plan();
  shorter.poses.resize(1);
  EXPECT_NE(resume_error(shorter).find("not in this plan"), std::string::npos);
  // Another robot: readings far from this controller's IK of the poses.
  std::string other = recorded;
  const size_t row = other.find("\n0,") + 3;
  other.replace(row, other.find(',', row) - row, "0.5");
  test::write_text(dir / "s.csv", other);
  EXPECT_NE(resume_error(plan()).find("another robot"), std::string::npos);
  test::write_text(dir / "s.csv", recorded);
  EXPECT_EQ(resume_error(plan()), "");  // the same plan resumes
}

// A stop request (the flag StopOnSignal sets) disables the drives at the next
// cycle and throws Interrupted; the samples taken before are on disk.
TEST(SamplingSession, StopRequestDisablesTheDrivesAndKeepsTheSamples) {
  const test::TempDir dir("stop");
  test::write_text(dir / "twin.yaml", hw_yaml("twin", "twin: {scenario: " + kScenario + "}\n"));
  auto hw = make_hardware(load_hardware_config((dir / "twin.yaml").string()));
  std::atomic<bool> stop{false};
  SampleLog log((dir / "s.csv").string(), false);
  std::string message;
  SessionPlan p = plan();
  SessionPlan first = p;
  first.poses.resize(2);
  EXPECT_EQ(run_sampling_session(*hw, first, log).taken, 2);
  auto hw2 = make_hardware(load_hardware_config((dir / "twin.yaml").string()));
  stop = true;  // requested before the first cycle of the resumed session
  try {
    run_sampling_session(*hw2, p, log, &stop);
  } catch (const Interrupted& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("drives disabled"), std::string::npos) << message;
  EXPECT_NE(message.find("2 samples kept"), std::string::npos) << message;
  EXPECT_EQ(hw2->state(), LifecycleState::kFinalized);
  EXPECT_EQ(read_samples_csv((dir / "s.csv").string()).size(), 2u);
}


// The dither figure: it starts and ends at rest at the pose (offset 0 and
// d offset / du = 0 at u = 0 and 1 under the motion profile), and its time
// average under the profile is 0 (so the mean pose is the pose): by the
// symmetry s(1 - u) = 1 - s(u) both sines are odd about u = 1/2.
TEST(SamplingSession, DitherFigureIsClosedRestsAtItsEndsAndAveragesToThePose) {
  const double r = 0.25;
  EXPECT_LT(dither_offset(0.0, r).norm(), 1e-15);
  EXPECT_LT(dither_offset(1.0, r).norm(), 1e-12);
  const double h = 1e-6;
  const auto at = [r](double u) { return dither_offset(motion_profile(u), r); };
  EXPECT_LT((at(h) - at(0.0)).norm() / h, 1e-5);
  EXPECT_LT((at(1.0) - at(1.0 - h)).norm() / h, 1e-5);
  // Hand-worked extremes: x reaches +-r at s = 1/4, 3/4; y reaches +-r/2 at s = 1/8.
  EXPECT_NEAR(dither_offset(0.25, r).x(), r, 1e-15);
  EXPECT_NEAR(dither_offset(0.75, r).x(), -r, 1e-15);
  EXPECT_NEAR(dither_offset(0.125, r).y(), r / 2, 1e-15);
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  const int n = 1000;
  for (int k = 1; k <= n; ++k) mean += at(static_cast<double>(k) / n) / n;
  EXPECT_LT(mean.norm(), 1e-12);
}

// Sampson distance (rad) of each sample's readings to the closed loops of
// geometry g (calib/residuals.hpp): the reading error, to first order.
std::vector<double> loop_gaps(const Geometry& g, const Samples& s) {
  std::vector<double> out;
  for (const Eigen::Vector3d& m : s.theta_m) {
    double r = NAN;
    const calib::MlResidual residual(m);
    residual(g.values.data(), &r);
    out.push_back(r);
  }
  return out;
}

double rms(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x * x;
  return std::sqrt(s / static_cast<double>(v.size()));
}

// Samples the plan on the twin of `scenario` with the given dither and
// returns the loop gaps of the twin's actual geometry at the readings.
std::vector<double> gaps_on_twin(const std::string& scenario, double dither_mm, const std::string& name) {
  const test::TempDir dir(name);
  test::write_text(dir / "twin.yaml", hw_yaml("twin", "twin: {scenario: " + scenario + "}\n"));
  const HardwareConfig c = load_hardware_config((dir / "twin.yaml").string());
  SessionPlan p = plan();
  p.poses = {{236.5, 260}, {196.5, 240}, {230, 225}, {205, 270}, {250, 250}, {190, 265}, {220, 290}, {215, 215}};
  p.dither_mm = dither_mm;
  auto hw = make_hardware(c);
  {
    SampleLog log((dir / "s.csv").string(), false);
    EXPECT_EQ(run_sampling_session(*hw, p, log).taken, 8);
  }
  return loop_gaps(c.twin->actual.geometry, read_samples_csv((dir / "s.csv").string()));
}

// Held still, a 17-bit encoder reads its angle rounded, whatever the
// averaging (the rounding of a standing encoder is the same every reading):
// the readings miss a closed loop of the actual mechanism by about a count /
// sqrt(12). Averaged along the dither figure (some 20 counts wide) the
// rounding averages out: at least 4 times closer (about 0.02 counts measured).
TEST(SamplingSession, DitherAveragesOutTheEncoderRounding) {
  const double still = rms(gaps_on_twin(kScenario, 0.0, "still"));
  const double dithered = rms(gaps_on_twin(kScenario, kDitherMm, "dither"));
  std::printf("loop gap rms: held still %.3f counts, dithered %.3f counts\n", still / kCount, dithered / kCount);
  EXPECT_GT(still, 0.1 * kCount);  // the rounding is there when held still
  EXPECT_LT(dithered, still / 4);
}

// With ideal encoders (no rounding, no noise) the dithered readings close the
// actual loops to numerical precision: subtracting the figure's commands
// leaves no error of its own (its curvature included): about 1e-3 counts
// measured, where averaging the raw readings leaves about 5e-3.
TEST(SamplingSession, DitherAddsNoErrorWithIdealEncoders) {
  const test::TempDir dir("ideal");
  std::string text = test::read_text(kScenario);
  text.replace(text.find("bits: 17"), 8, "bits: 0");
  const size_t robot = text.find("../../models/");
  text.replace(robot, 13, kSrc + "/models/");
  test::write_text(dir / "ideal.yaml", text);
  const double gap = rms(gaps_on_twin((dir / "ideal.yaml").string(), kDitherMm, "ideal_run"));
  std::printf("ideal encoders, dithered: loop gap rms %.2e counts\n", gap / kCount);
  EXPECT_LT(gap, 2e-3 * kCount);  // averaging the raw readings instead: about 5e-3 counts
}

}  // namespace
}  // namespace gpm::hw
