// Tests of sim/simulate.cpp: a run is bit-reproducible from its seed, bad
// targets are refused with the pose and the reason, the output files follow
// their contracts and are written all or nothing, the tracking watch stops a
// run that leaves its plan (samples kept), and a trajectory plan keeps
// sampling.path_margin or is refused before anything moves; a plan made again
// in the same thread (the controller's verdicts remembered) equals one made
// afresh, the actual mechanism still checked at every point.
#include "sim/simulate.hpp"
#include "models/data_dir.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>
#include <unistd.h>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "models/errors.hpp"
#include "models/robot_yaml.hpp"
#include "models/samples.hpp"

namespace gpm::sim {
namespace fs = std::filesystem;
namespace {

const std::string kModels = gpm::models_dir();

Scenario parse(const std::string& text) { return parse_scenario(text, "s.yaml", kModels); }

const char* kSmall = R"(
seed: 5
actual: {perturb: {base_mm: 0.3, link_mm: 0.3, offset_rad: 0.01}}
encoder: {noise_rad: 1e-5}
sampling: {pattern: disc, radius: 40, count: 4, settle: {hold_s: 0.01}, average_s: 0.02}
path: {shape: line, from: [200, 250], to: [230, 250], duration_s: 0.2}
)";

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string error_of(const Scenario& s) {
  try {
    run_simulation(s);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

fs::path temp_dir(const std::string& tag) {
  return fs::temp_directory_path() / ("gpm_test_simulate_" + tag + std::to_string(::getpid()));
}

TEST(Simulate, SameSeedGivesIdenticalFilesAndAnotherSeedDoesNot) {
  const fs::path a = temp_dir("a"), b = temp_dir("b"), c = temp_dir("c");
  write_simulation(run_simulation(parse(kSmall)), a.string());
  write_simulation(run_simulation(parse(kSmall)), b.string());
  std::string other = kSmall;
  other.replace(other.find("seed: 5"), 7, "seed: 6");
  write_simulation(run_simulation(parse(other)), c.string());
  for (const char* f : {"samples.csv", "trajectory.csv", "actual.yaml", "model.xml"}) {
    const std::string ta = read_text(a / f);
    EXPECT_GT(ta.size(), 100u) << f;
    EXPECT_EQ(ta, read_text(b / f)) << f;
    EXPECT_NE(ta, read_text(c / f)) << f;
  }
  for (const auto& d : {a, b, c}) fs::remove_all(d);
}

TEST(Simulate, OutputsFollowTheirContracts) {
  const fs::path dir = temp_dir("contract");
  const SimulationResult r = run_simulation(parse(kSmall));
  write_simulation(r, dir.string());
  const Samples s = read_samples_csv((dir / "samples.csv").string());
  ASSERT_EQ(s.size(), 4u);
  EXPECT_TRUE(s.has_xy);
  EXPECT_EQ(s.xy[2], r.samples[2].xy_mm);
  EXPECT_EQ(load_robot((dir / "actual.yaml").string()), r.actual);
  EXPECT_EQ(read_text(dir / "model.xml"), r.model_xml);
  const std::string traj = read_text(dir / "trajectory.csv");
  EXPECT_EQ(traj.rfind("t,x_des,y_des,x,y,theta_m1,theta_m2,theta_m3,tau1,tau2,tau3,violation_m\n", 0), 0u);
  EXPECT_EQ(static_cast<size_t>(std::count(traj.begin(), traj.end(), '\n')), r.log.rows.size() + 1);
  EXPECT_LT(r.max_violation_m, 1e-6);
  // No temporary folder left behind.
  for (const auto& e : fs::directory_iterator(dir)) EXPECT_EQ(e.path().filename().string()[0] != '.', true);
  fs::remove_all(dir);
}

TEST(Simulate, UnreachablePoseIsNamedWithTheReach) {
  const std::string e = error_of(parse("sampling: {pattern: list, poses: [[216.5, 250], [216.5, 700]]}"));
  EXPECT_NE(e.find("sampling: pose 1 (216.5000, 700.0000)"), std::string::npos) << e;
  EXPECT_NE(e.find("outside its reach"), std::string::npos) << e;
}

TEST(Simulate, PoseNearASingularityIsRefused) {
  // (216.5, 250) + 200 mm along x: chain 1 nearly stretched (|A1 O| = 416.5 of 488).
  const std::string e = error_of(parse(R"(
robot:
  geometry: {xa1: 0, ya1: 250, xa2: 433, ya2: 0, xa3: 433, ya3: 500, la1: 244, la2: 244, la3: 244,
             lb1: 244, lb2: 244, lb3: 244, dth1: 0, dth2: 0, dth3: 0}
  limits: {min_transmission: 0.9}
sampling: {pattern: list, poses: [[216.5, 250], [300, 250]]}
)"));
  EXPECT_NE(e.find("sampling: pose"), std::string::npos) << e;
  EXPECT_NE(e.find("singularity"), std::string::npos) << e;
}

TEST(Simulate, PathOutOfReachIsRefused) {
  const std::string e = error_of(parse("path: {shape: circle, radius: 400, period_s: 1}"));
  EXPECT_NE(e.find("path: point at t = 0.000 s"), std::string::npos) << e;
}

// Joint 1 torque-off, the actual mechanism the controller's: an encoder slip
// of joint 2 at 0.6 s (0.08 rad over 0.05 s) moves the hub about 20 mm while
// the drives still track their commands; the torque-off joint's reading shows
// it, and the watch stops the run with the samples taken before.
Scenario slipping_joint(double bound_mm) {
  Scenario s = parse(fmt::format(R"(
servo: {{modes: [torque_off, position, position], max_tracking_mm: {}}}
sampling: {{pattern: list, poses: [[216.5, 250], [230, 260], [200, 240], [225, 235]], settle: {{hold_s: 0.01}},
           average_s: 0.02}}
)", bound_mm));
  GeometryEvent slip;
  slip.at_s = 0.6;
  slip.over_s = 0.05;
  slip.delta[kDth2] = 0.08;
  s.twin.events.push_back(slip);
  return s;
}

TEST(Simulate, TrackingWatchStopsTheRunOnAForcedDeviationAndKeepsTheSamples) {
  Scenario calm = slipping_joint(5.0);
  calm.twin.events.clear();
  EXPECT_EQ(run_simulation(calm).samples.size(), 4u);  // no slip: no stop
  try {
    run_simulation(slipping_joint(5.0));
    FAIL() << "no tracking stop";
  } catch (const TrackingStop& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("tracking: at t = 0.6", 0), 0u) << what;
    EXPECT_NE(what.find("beyond servo.max_tracking_mm 5 mm: drives stopped"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos);
    EXPECT_GE(e.samples.size(), 1u);
    EXPECT_LT(e.samples.size(), 4u);
    ASSERT_FALSE(e.rows.empty());
    EXPECT_LT(e.rows.back().t, 0.7);
  }
  // gpm simulate keeps what was measured: samples.csv and the trajectory up to the stop.
  const fs::path dir = temp_dir("stop");
  EXPECT_THROW(simulate_to_folder(slipping_joint(5.0), dir.string()), TrackingStop);
  EXPECT_GE(read_samples_csv((dir / "samples.csv").string()).theta_m.size(), 1u);
  EXPECT_TRUE(fs::exists(dir / "trajectory.csv"));
  fs::remove_all(dir);
}

// Eleven poses round home sampled on the fly by the five-bar of drives 2 and 3.
constexpr const char* kElevenOnTheFly = R"(
servo: {modes: [torque_off, position, position]}
sampling:
  pattern: trajectory
  count: 11
  poses: [[216.5, 250], [236.5, 260], [196.5, 240], [230, 225], [200, 270], [250, 250], [180, 250], [216.5, 290],
          [216.5, 210], [240, 280], [190, 220]]
)";

// A trajectory plan whose margin cannot be kept is refused (InputError: one
// line, exit 2) before the twin is built; the same poses with the default
// margin run.
TEST(Simulate, TrajectoryThatCannotKeepTheMarginIsRefusedBeforeAnythingMoves) {
  const std::string plan = kElevenOnTheFly;
  EXPECT_GT(run_simulation(parse(plan)).samples.size(), 11u);
  const std::string e = error_of(parse(plan + "  path_margin: {singularity: 0.8}\n"));
  EXPECT_EQ(e.rfind("s.yaml: sampling: excitation path refused before anything moves: ", 0), 0u) << e;
  EXPECT_NE(e.find("singularity"), std::string::npos) << e;
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
}

// The controller's verdicts are remembered per thread: a plan made again
// equals one made afresh in a new thread, and a scenario with another margin
// (here one the poses cannot keep) is not answered from the memo.
TEST(Simulate, PlanMadeAgainEqualsOneMadeAfreshAndAnotherMarginIsCheckedAgain) {
  const Scenario s = parse(kElevenOnTheFly);
  Scenario strict = s;
  strict.sampling->margin.singularity = 0.8;  // a margin the poses cannot keep
  const auto plan_or_refusal = [](const Scenario& sc) -> std::pair<WaypointPath, std::string> {
    try {
      return {excitation_plan(sc, sc.sampling->poses), ""};
    } catch (const InputError& e) {
      return {WaypointPath{}, e.what()};
    }
  };
  std::pair<WaypointPath, std::string> fresh, fresh_strict;
  std::thread([&] { fresh = plan_or_refusal(s); }).join();
  std::thread([&] { fresh_strict = plan_or_refusal(strict); }).join();
  ASSERT_EQ(fresh.second, "");
  EXPECT_NE(fresh_strict.second.find("refused before anything moves"), std::string::npos) << fresh_strict.second;
  for (int round = 0; round < 2; ++round) {
    const auto again = plan_or_refusal(s);
    EXPECT_EQ(again.first.t, fresh.first.t);
    EXPECT_EQ(again.first.p, fresh.first.p);
    EXPECT_EQ(again.first.v, fresh.first.v);
    EXPECT_EQ(plan_or_refusal(strict).second, fresh_strict.second);
  }
}

TEST(Simulate, NothingIsWrittenWhenTheFolderCannotBeWritten) {
  const fs::path file = temp_dir("file");
  { std::ofstream(file) << "x"; }
  const SimulationResult r = run_simulation(parse(kSmall));
  EXPECT_THROW(write_simulation(r, file.string()), InputError);  // a file, not a folder
  EXPECT_THROW(write_simulation(r, (file / "sub").string()), InputError);
  EXPECT_EQ(read_text(file), "x");
  fs::remove(file);
}

TEST(Simulate, StreamedTrajectoryEqualsTheInMemoryOneAndKeepsNoRows) {
  const fs::path a = temp_dir("mem"), b = temp_dir("stream");
  write_simulation(run_simulation(parse(kSmall)), a.string());
  const SimulationResult r = simulate_to_folder(parse(kSmall), b.string());
  EXPECT_TRUE(r.log.rows.empty()) << "streaming must not hold the log in memory";
  for (const char* f : {"samples.csv", "trajectory.csv", "actual.yaml", "model.xml"})
    EXPECT_EQ(read_text(a / f), read_text(b / f)) << f;
  const std::string traj = read_text(b / "trajectory.csv");
  EXPECT_EQ(static_cast<long>(std::count(traj.begin(), traj.end(), '\n')), r.log.count + 1);
  EXPECT_EQ(std::distance(fs::directory_iterator(b), fs::directory_iterator{}), 4) << "no staging folder left";
  for (const auto& d : {a, b}) fs::remove_all(d);
}

TEST(Simulate, ThermalRunsLogTheActualParametersAtEachRow) {
  const fs::path dir = temp_dir("thermal");
  std::string text = kSmall;
  text += "effects: {thermal: {expansion_per_K: 1.0e-4, rise_K: 10, time_constant_s: 1}}\n";
  simulate_to_folder(parse(text), dir.string());
  std::istringstream in(read_text(dir / "trajectory.csv"));
  std::string header, line, last;
  std::getline(in, header);
  EXPECT_NE(header.find(",violation_m,growth,xa1,ya1,xa2,ya2,xa3,ya3,la1,la2,la3,lb1,lb2,lb3"), std::string::npos);
  while (std::getline(in, line)) last = line;
  // Last row: t and la1 (columns 0 and 19) satisfy la1 = L0 (1 + alpha rise (1 - exp(-t / tau))).
  std::vector<double> v;
  std::stringstream ls(last);
  for (std::string f; std::getline(ls, f, ',');) v.push_back(std::stod(f));
  ASSERT_EQ(v.size(), 25u);
  const double la1_0 = load_robot((dir / "actual.yaml").string()).geometry.la_(0);  // at t = 0
  EXPECT_NEAR(v[19], la1_0 * (1.0 + 1e-3 * (1.0 - std::exp(-v[0]))), 1e-9);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace gpm::sim
