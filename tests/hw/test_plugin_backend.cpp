// Tests of hw/backends/plugin_backend.cpp (with the C ABI of
// hw/plugin/gpm_backend_plugin.h and the sample plugin
// hw/plugin/examples/motion_card_plugin.cpp): the sample plugin runs the
// lifecycle behind the safety supervisor and reads what the twin backend
// reads, cycle for cycle; its sampling session agrees with the twin
// backend's; a plugin of another ABI or API version is refused naming the file
// and both versions; a plugin that breaks the contract (no table, a null
// function, error codes, NaN readings, stale read times, an exception) gives a
// HardwareError, never a crash; a plugin built in another build tree against
// the header alone loads and runs.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include <dlfcn.h>
#include <fmt/format.h>

#include "hw/backends/plugin_backend.hpp"
#include "hw/hardware_config.hpp"
#include "hw/hw_errors.hpp"
#include "hw/procedures/sampling_session.hpp"
#include "hw/safety_supervisor.hpp"
#include "hw_test_util.hpp"
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

std::string hw_yaml(const std::string& backend, const std::string& extra) {
  return "backend: " + backend + "\nrate_hz: 250\ncontroller: " + kSrc + "/models/gpm2002.yaml\n" + extra +
         test::kSafetyYaml;
}

// Loads the hardware file text written to dir/name.
HardwareConfig config_of(const test::TempDir& dir, const std::string& name, const std::string& text) {
  test::write_text(dir / name, text);
  return load_hardware_config((dir / name).string());
}

// The sample plugin's hardware file over the test scenario's twin.
std::string card_yaml(const std::string& extra_config = "") {
  return hw_yaml("plugin", fmt::format("plugin: {{library: {}, config: {{scenario: {}{}}}}}\n", GPM_MOTION_CARD_PLUGIN,
                                       kScenario, extra_config));
}

// The readings of the nominal robot at home (the scripted plugins start there).
Eigen::Vector3d home_readings() {
  const Robot r;
  return readings_from_active(r.geometry, inverse_kinematics(r.geometry, r.home, r.branch).theta_a);
}

// A scripted plugin's hardware file; script: more keys of its configuration.
std::string scripted_yaml(const std::string& script, const char* library = GPM_SCRIPTED_PLUGIN) {
  const Eigen::Vector3d q = home_readings();
  return hw_yaml("plugin", fmt::format("plugin: {{library: {}, config: {{start: [{}, {}, {}]{}}}}}\n", library, q[0],
                                       q[1], q[2], script));
}

// The message of the error E that f throws ("" if none).
template <class E, class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  return "";
}

// A counter the scripted plugin exports for tests (dlsym on the loaded library).
long scripted_counter(const char* name) {
  void* lib = ::dlopen(GPM_SCRIPTED_PLUGIN, RTLD_LAZY | RTLD_NOLOAD);
  if (!lib) return -1;
  const auto f = reinterpret_cast<long (*)()>(::dlsym(lib, name));
  const long v = f ? f() : -1;
  ::dlclose(lib);
  return v;
}

// The same hold commands through both backends: the plugin reads, cycle for
// cycle, what the twin backend reads (the card wraps the same twin), and
// stamps every axis with the one read time of the card's own clock.
TEST(PluginBackend, SamplePluginRunsTheLifecycleBehindTheSupervisor) {
  const test::TempDir dir("plugin_life");
  const HardwareConfig pc = config_of(dir, "card.yaml", card_yaml(", clock_offset_s: 1000.0"));
  const HardwareConfig tc = config_of(dir, "twin.yaml", hw_yaml("twin", "twin: {scenario: " + kScenario + "}\n"));
  auto card = make_hardware(pc);
  auto twin = make_hardware(tc);
  EXPECT_EQ(card->describe(), fmt::format("supervised plugin motion-card-sim ({})", GPM_MOTION_CARD_PLUGIN));
  EXPECT_TRUE(card->simulated_time());
  card->configure();
  twin->configure();
  EXPECT_EQ(card->last_state().theta_m, twin->last_state().theta_m);
  for (const DriveStatus& d : card->last_state().drive) EXPECT_FALSE(d.enabled);
  card->activate();
  twin->activate();
  const HardwareCommand hold = hold_command(card->last_state().theta_m);
  const double dt = card->period_s();
  for (int k = 1; k <= 100; ++k) {
    const double t = k * dt;
    card->write(hold, t);
    twin->write(hold, t);
    const HardwareState& c = card->read(t);
    const HardwareState& w = twin->read(t);
    ASSERT_EQ(c.theta_m, w.theta_m) << "cycle " << k;
    ASSERT_EQ(c.velocity, w.velocity) << "cycle " << k;
    ASSERT_EQ(c.torque, w.torque) << "cycle " << k;
    EXPECT_EQ(c.time_s, t);
    EXPECT_EQ(c.read_time_s, Eigen::Vector3d(Eigen::Vector3d::Constant(t))) << "the card clock's origin does not reach the host";
    EXPECT_TRUE(c.torque_reported);
    for (const DriveStatus& d : c.drive) EXPECT_TRUE(d.enabled);
  }
  card->deactivate();
  for (const DriveStatus& d : card->read(101 * dt).drive) EXPECT_FALSE(d.enabled);
  card->shutdown();
  EXPECT_EQ(card->state(), LifecycleState::kFinalized);
  EXPECT_THROW(card->configure(), LifecycleError);
}

// The example hardware file (hw/plugin/examples/motion_card.yaml), its
// relative paths made absolute and its library the one of this build.
TEST(PluginBackend, ExampleHardwareFileLoadsAndConfigures) {
  const test::TempDir dir("plugin_example");
  std::string text = test::read_text(kSrc + "/hw/plugin/examples/motion_card.yaml");
  for (size_t at; (at = text.find("../../../")) != std::string::npos;) text.replace(at, 9, kSrc + "/");
  const std::string lib = kSrc + "/build/hw/libgpm_motion_card.so";
  ASSERT_NE(text.find(lib), std::string::npos);
  text.replace(text.find(lib), lib.size(), GPM_MOTION_CARD_PLUGIN);
  auto hw = make_hardware(config_of(dir, "motion_card.yaml", text));
  hw->configure();
  EXPECT_EQ(hw->state(), LifecycleState::kInactive);
  EXPECT_EQ(hw->period_s(), 1.0 / 250);
}

TEST(PluginBackend, SamplePluginWithoutTorqueSaysSo) {
  const test::TempDir dir("plugin_torque");
  auto card = make_hardware(config_of(dir, "card.yaml", card_yaml(", report_torque: false")));
  card->configure();
  EXPECT_FALSE(card->last_state().torque_reported);
  EXPECT_EQ(card->last_state().torque, Eigen::Vector3d(Eigen::Vector3d::Zero()));
}

// A card without a latch (poll_in_turn_s 1 ms): axis i is read (2 - i) ms
// before the reading's time and stamped so; carried to one instant by their
// speeds (hw::readings_at_first_read, then to the reading's time) the
// readings are those of a card with a latch over the same twin within a
// count, while as read they are several counts off it.
TEST(PluginBackend, SamplePluginPolledInTurnStampsEachAxis) {
  const test::TempDir dir("plugin_poll");
  auto polled = make_hardware(config_of(dir, "polled.yaml", card_yaml(", poll_in_turn_s: 0.001")));
  auto latch = make_hardware(config_of(dir, "latch.yaml", card_yaml()));
  polled->configure();
  latch->configure();
  polled->activate();
  latch->activate();
  const Robot r;
  const double dt = polled->period_s();
  // Along a line from where the readings put the controller's robot, speeding
  // up to 100 mm/s over 0.3 s (within the safety limits): every joint moves.
  const Eigen::Vector3d theta0 = polled->last_state().theta_m;
  const auto start = forward_kinematics(r.geometry, active_from_readings(r.geometry, theta0));
  ASSERT_TRUE(start);
  const auto readings_at = [&](const Eigen::Vector2d& q) {
    return readings_from_active(r.geometry, inverse_kinematics(r.geometry, q, r.branch).theta_a);
  };  // (commanded from the readings as they start: the twin is not the controller's model)
  double off_as_read = 0.0;
  for (int k = 1; k <= 100; ++k) {
    const double t = k * dt;
    const double along = t < 0.3 ? t * t / (2 * 0.3) : t - 0.15;  // s of path at 1 mm/s
    const Eigen::Vector2d p = start->p + Eigen::Vector2d(80.0, 60.0) * along;
    const HardwareCommand c = hold_command(theta0 + readings_at(p) - readings_at(start->p));
    polled->write(c, t);
    latch->write(c, t);
    const HardwareState& a = polled->read(t);
    const HardwareState& b = latch->read(t);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(a.read_time_s[i], t - (2 - i) * 0.001, 1e-9) << "cycle " << k;
    const Eigen::Vector3d at_t = readings_at_first_read(a) + a.velocity * (t - a.read_time_s[0]);
    if (k > 50) {  // moving
      for (int i = 0; i < 3; ++i) EXPECT_NEAR(at_t[i], b.theta_m[i], 1.01 * kCount) << "cycle " << k << " axis " << i + 1;
      off_as_read = std::max(off_as_read, (a.theta_m - b.theta_m).cwiseAbs().maxCoeff());
    }
  }
  EXPECT_GT(off_as_read, 4 * kCount) << "the test could not fail";
}

// A plugin's refusal of its configuration is bad input naming the hardware file.
TEST(PluginBackend, SamplePluginRefusesABadConfiguration) {
  const test::TempDir dir("plugin_cfg");
  const HardwareConfig c = config_of(dir, "card.yaml", card_yaml(", clock: 3"));
  const std::string e = error_of<InputError>([&] { make_hardware(c); });
  EXPECT_NE(e.find("card.yaml: plugin.config: backend plugin motion-card-sim refused its configuration"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("clock"), std::string::npos) << e;
}

// The plugin backend settings of library, with a scripted plugin's configuration.
PluginBackendConfig library_config(const std::string& library) {
  PluginBackendConfig c;
  c.library = library;
  c.config_text = "{start: [1.1, 3.1, 4.8]}";
  c.base_dir = "/";
  c.source = "hw.yaml";
  return c;
}

TEST(PluginBackend, OtherAbiOrApiVersionIsRefusedNamingTheFileAndBothVersions) {
  const std::string abi = error_of<InputError>([] { PluginBackend b(library_config(GPM_BAD_ABI_PLUGIN)); });
  EXPECT_EQ(abi, fmt::format("{}: backend plugin of ABI version 99, this gpm has ABI version 1: rebuild it against "
                             "this gpm's hw/plugin/gpm_backend_plugin.h",
                             GPM_BAD_ABI_PLUGIN));
  const std::string api = error_of<InputError>([] { PluginBackend b(library_config(GPM_BAD_API_PLUGIN)); });
  EXPECT_NE(api.find(fmt::format("{}: backend plugin of API version 2.0, this gpm has API version 1.0", GPM_BAD_API_PLUGIN)),
            std::string::npos)
      << api;
  // Through the hardware file, before anything is configured.
  const test::TempDir dir("plugin_abi");
  const HardwareConfig c = config_of(dir, "hw.yaml", scripted_yaml("", GPM_BAD_ABI_PLUGIN));
  EXPECT_EQ(error_of<InputError>([&] { make_hardware(c); }), abi);
}

TEST(PluginBackend, AFileThatIsNoPluginIsRefused) {
  const test::TempDir dir("plugin_none");
  test::write_text(dir / "libfake.so", "not a library");
  const std::string e = error_of<InputError>([&] { PluginBackend b(library_config((dir / "libfake.so").string())); });
  EXPECT_NE(e.find((dir / "libfake.so").string() + ": cannot load the backend plugin"), std::string::npos) << e;
  const std::string n = error_of<InputError>([] { PluginBackend b(library_config(GPM_NO_ENTRY_PLUGIN)); });
  EXPECT_NE(n.find("exports no function gpm_backend_plugin_entry"), std::string::npos) << n;
}

TEST(PluginBackend, NoTableOrANullFunctionIsAHardwareError) {
  const std::string t = error_of<HardwareError>([] { PluginBackend b(library_config(GPM_NULL_TABLE_PLUGIN)); });
  EXPECT_NE(t.find(fmt::format("{}: backend plugin gave no table for ABI version 1", GPM_NULL_TABLE_PLUGIN)),
            std::string::npos)
      << t;
  const std::string f = error_of<HardwareError>([] { PluginBackend b(library_config(GPM_NULL_READ_PLUGIN)); });
  EXPECT_NE(f.find("has no function 'read' (a null pointer in its table)"), std::string::npos) << f;
}

// Runs hold cycles on hw (configured and activated here) until it throws;
// returns the message, or "" when all cycles pass.
std::string run_until_error(SafetySupervisor& hw, int cycles) {
  return error_of<HardwareError>([&] {
    hw.configure();
    hw.activate();
    const HardwareCommand hold = hold_command(hw.last_state().theta_m);
    for (int k = 1; k <= cycles; ++k) {
      hw.write(hold, k * hw.period_s());
      hw.read(k * hw.period_s());
    }
  });
}

TEST(PluginBackend, ErrorCodesBecomeHardwareErrorsWithThePluginsMessage) {
  const test::TempDir dir("plugin_codes");
  auto good = make_hardware(config_of(dir, "good.yaml", scripted_yaml("")));
  EXPECT_EQ(run_until_error(*good, 20), "");
  const long stops = scripted_counter("gpm_test_plugin_emergency_stops");
  auto hw = make_hardware(config_of(dir, "read.yaml", scripted_yaml(", fail: read, code: 3, after: 5")));
  const std::string e = run_until_error(*hw, 20);
  EXPECT_NE(e.find("plugin scripted: read failed (no answer from the controller, code 3): scripted failure of read "
                   "(card timeout on axis 2)"),
            std::string::npos)
      << e;
  EXPECT_EQ(hw->state(), LifecycleState::kError);
  EXPECT_GT(scripted_counter("gpm_test_plugin_emergency_stops"), stops) << "the drives were not stopped";
  // An unknown code, and a failure of configure: the same, with the code.
  auto c = make_hardware(config_of(dir, "cfg.yaml", scripted_yaml(", fail: configure, code: 77")));
  const std::string ce = run_until_error(*c, 1);
  EXPECT_NE(ce.find("configure failed (unknown code, code 77): scripted failure of configure"), std::string::npos)
      << ce;
  // create: a refused configuration is bad input; another code a hardware error.
  const HardwareConfig refused = config_of(dir, "refused.yaml", scripted_yaml(", fail: create, code: 2"));
  EXPECT_NE(error_of<InputError>([&] { make_hardware(refused); }).find("refused.yaml: plugin.config"),
            std::string::npos);
  const HardwareConfig failed = config_of(dir, "failed.yaml", scripted_yaml(", fail: create, code: 4"));
  EXPECT_NE(error_of<HardwareError>([&] { make_hardware(failed); }).find("create failed (drive fault, code 4)"),
            std::string::npos);
}

TEST(PluginBackend, NanReadingsAndStaleReadTimesAreHardwareErrors) {
  const test::TempDir dir("plugin_nan");
  auto nan = make_hardware(config_of(dir, "nan.yaml", scripted_yaml(", nan_after: 4")));
  const std::string e = run_until_error(*nan, 20);
  EXPECT_NE(e.find("plugin scripted: axis 2 reading is not a finite number (nan)"), std::string::npos) << e;
  EXPECT_EQ(nan->state(), LifecycleState::kError);
  auto stale = make_hardware(config_of(dir, "stale.yaml", scripted_yaml(", stale_after: 4")));
  const std::string s = run_until_error(*stale, 20);
  EXPECT_NE(s.find("plugin scripted: axis 3 was read at"), std::string::npos) << s;
  EXPECT_THROW(nan->read(1.0), LifecycleError);  // stopped: no further call reaches the plugin
}

// The ABI allows no exception across it; one that a C++ plugin lets escape
// anyway is caught here (GCC, x86-64) and is a HardwareError, drives stopped.
TEST(PluginBackend, AnEscapingExceptionIsAHardwareError) {
  const test::TempDir dir("plugin_throw");
  const long stops = scripted_counter("gpm_test_plugin_emergency_stops");
  auto hw = make_hardware(config_of(dir, "throw.yaml", scripted_yaml(", throw_read: 3")));
  const std::string e = run_until_error(*hw, 20);
  EXPECT_NE(e.find("plugin scripted: read let an exception escape"), std::string::npos) << e;
  EXPECT_EQ(hw->state(), LifecycleState::kError);
  EXPECT_GT(scripted_counter("gpm_test_plugin_emergency_stops"), stops);
}

// A plugin that reports no velocity: the backend differentiates the readings
// over their read times (ideal drives read exactly the last command).
TEST(PluginBackend, VelocityNotReportedIsTheDifferenceOfTheReadings) {
  PluginBackendConfig c = library_config(GPM_SCRIPTED_PLUGIN);
  c.period_s = 0.002;
  PluginBackend b(c);
  b.configure();
  b.activate();
  HardwareCommand cmd = hold_command(b.last_state().theta_m);
  b.read(0.002);
  cmd.theta_m[1] += 0.001;
  b.write(cmd, 0.004);
  const HardwareState& s = b.read(0.004);
  EXPECT_NEAR(s.velocity[1], 0.001 / 0.002, 1e-9);
  EXPECT_EQ(s.velocity[0], 0.0);
  EXPECT_FALSE(s.torque_reported);
  EXPECT_EQ(s.read_time_s, Eigen::Vector3d(0.004, 0.004, 0.004));
}

// Four poses around home, as in tests/hw/test_sampling_session.cpp.
SessionPlan plan() {
  SessionPlan p;
  p.poses = {{236.5, 260}, {196.5, 240}, {230, 225}, {205, 270}};
  p.options.move_speed_mm_s = 150;
  p.options.settle = {0.001, 0.2, 3.0};
  p.options.average_s = 0.1;
  return p;
}

// Runs plan through the hardware file text; returns the samples.
Samples run_session(const test::TempDir& dir, const std::string& name, const std::string& text) {
  auto hw = make_hardware(config_of(dir, name + ".yaml", text));
  SampleLog log((dir / (name + ".csv")).string(), false);
  EXPECT_EQ(run_sampling_session(*hw, plan(), log).taken, 4);
  return read_samples_csv((dir / (name + ".csv")).string());
}

TEST(PluginBackend, SamplePluginSessionAgreesWithTheTwinBackend) {
  const test::TempDir dir("plugin_session");
  const Samples twin = run_session(dir, "twin", hw_yaml("twin", "twin: {scenario: " + kScenario + "}\n"));
  const Samples card = run_session(dir, "card", card_yaml(", clock_offset_s: 37.5"));
  ASSERT_EQ(twin.size(), 4u);
  ASSERT_EQ(card.size(), 4u);
  double worst = 0.0;
  for (size_t k = 0; k < 4; ++k)
    for (int i = 0; i < 3; ++i) worst = std::max(worst, std::abs(card.theta_m[k][i] - twin.theta_m[k][i]));
  EXPECT_LE(worst, kCount * 1.0001) << "worst difference " << worst / kCount << " counts";
  std::printf("sample plugin vs twin backend: worst difference %.3f encoder counts\n", worst / kCount);
}

// A plugin in plain C99, configured and built with cmake in its own build
// tree against a copy of the header laid out as an installed gpm's
// (P/include/gpm/hw/plugin), then sampled through: with ideal drives each
// sample is the controller's IK of its pose.
TEST(PluginBackend, PluginBuiltInAnotherTreeLoadsAndRuns) {
  const test::TempDir dir("plugin_tree");
  const fs::path include = dir / "prefix/include/gpm/hw/plugin";
  fs::create_directories(include);
  fs::copy_file(kSrc + "/hw/plugin/gpm_backend_plugin.h", include / "gpm_backend_plugin.h");
  const fs::path log = dir / "build.log";
  const std::string cmd = fmt::format(
      "'{0}' -S '{1}/tests/hw/plugin_out_of_tree' -B '{2}/build' -G '{3}' -DCMAKE_MAKE_PROGRAM='{4}' "
      "-DCMAKE_PREFIX_PATH='{2}/prefix' >'{5}' 2>&1 && '{0}' --build '{2}/build' >>'{5}' 2>&1",
      GPM_CMAKE_COMMAND, kSrc, dir.path().string(), GPM_CMAKE_GENERATOR, GPM_CMAKE_MAKE_PROGRAM, log.string());
  ASSERT_EQ(std::system(cmd.c_str()), 0) << test::read_text(log);
  const Eigen::Vector3d q = home_readings();
  test::write_text(dir / "start.txt", fmt::format("{} {} {}\n", q[0], q[1], q[2]));
  const HardwareConfig c =
      config_of(dir, "hw.yaml", hw_yaml("plugin", "plugin: {library: build/libideal_drives.so, config: start.txt}\n"));
  auto hw = make_hardware(c);
  EXPECT_EQ(hw->describe(), "supervised plugin ideal-drives (" + (fs::absolute(dir.path()) / "build/libideal_drives.so").lexically_normal().string() + ")");
  SessionPlan p = plan();
  p.poses.resize(2);
  SampleLog samples((dir / "s.csv").string(), false);
  EXPECT_EQ(run_sampling_session(*hw, p, samples).taken, 2);
  const Samples s = read_samples_csv((dir / "s.csv").string());
  ASSERT_EQ(s.size(), 2u);
  const Robot& r = c.controller;
  for (size_t k = 0; k < 2; ++k) {
    const Eigen::Vector3d ik = readings_from_active(r.geometry, inverse_kinematics(r.geometry, p.poses[k], r.branch).theta_a);
    EXPECT_LT((s.theta_m[k] - ik).cwiseAbs().maxCoeff(), 1e-9) << "sample " << k;
  }
}

}  // namespace
}  // namespace gpm::hw
