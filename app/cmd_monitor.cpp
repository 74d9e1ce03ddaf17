// gpm monitor SCENARIO.yaml -o DIR [--model CALIBRATED.yaml]: the robot's
// normal job (scenario `operation:`) on the twin, with `events:` changing the
// actual mechanism and the drift monitor in the servo loop; writes
// DIR/alarms.csv, estimates.csv, summary.json and report.md/html
// (run/monitor_run.hpp). Bad input exits 2 with one line.
#include <cstdio>
#include <unistd.h>
#include <limits>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "app/commands.hpp"
#include "calib/result_yaml.hpp"
#include "models/errors.hpp"
#include "models/robot_yaml.hpp"
#include "run/monitor_run.hpp"
#include "sim/twin.hpp"

namespace gpm::cli {
namespace {

struct MonitorOptions {
  std::string scenario;
  std::string out;
  std::string model;
  std::string hardware;
};

}  // namespace

void add_monitor(CLI::App& app) {
  auto opt = std::make_shared<MonitorOptions>();
  auto* cmd = app.add_subcommand(
      "monitor", "Drift monitoring in normal operation: alarms (what changed, when) and tracked parameters");
  cmd->add_option("scenario", opt->scenario, "Scenario file with operation: (and events:), see scenarios/SCHEMA.md")
      ->required();
  cmd->add_option("-o,--out", opt->out, "Output folder: alarms.csv, estimates.csv, summary.json, report.md")->required();
  cmd->add_option("--model", opt->model, "The controller's model (robot or calibration result file); default: the scenario's robot");
  cmd->add_option("--hardware", opt->hardware, "Hardware file (not yet: the monitor runs on the twin)");
  cmd->callback([opt] {
    if (!opt->hardware.empty())
      throw InputError("gpm monitor --hardware: monitoring a live robot is not available yet; run it on the twin "
                       "(omit --hardware)");
    sim::Scenario s = sim::load_scenario(opt->scenario);
    Robot controller = s.controller;
    if (!opt->model.empty()) controller = load_robot(opt->model);
    std::array<double, kNumParams> prior;
    prior.fill(std::numeric_limits<double>::quiet_NaN());
    scenario::MonitorOutcome o;
    try {
      // Progress on a terminal only (a log file gets the summary alone).
      const bool tty = isatty(STDERR_FILENO) != 0;
      o = scenario::run_monitor(s, controller, prior, [tty](double t, double T) {
        if (tty) std::fprintf(stderr, "\rgpm monitor: %.0f of %.0f s of operation", t, T);
      });
      if (tty) std::fprintf(stderr, "\n");
    } catch (const sim::SimError& e) {
      throw InputError(fmt::format("{}: {}", opt->scenario, e.what()));
    }
    const scenario::MonitorExpect expect = scenario::load_monitor_expect(opt->scenario);
    scenario::write_monitor(o, opt->out);
    const auto checks = scenario::check_monitor(o, expect);
    int failed = 0;
    for (const auto& c : checks) failed += c.passed ? 0 : 1;
    fmt::print("scenario   {} ({})\n", s.name, opt->scenario);
    fmt::print("operation  {:.1f} s, {} servo cycles, {:.1f} s wall\n", o.simulated_s, o.cycles, o.wall_s);
    fmt::print("alarms     {} ({} false; stated rate {} per hour)\n", o.alarms.size(), o.false_alarms,
               o.model.settings.false_alarms_per_hour);
    for (const auto& d : o.detections) {
      if (d.detected_s)
        fmt::print("event {}    at {:.3f} s detected at {:.3f} s (delay {:.3f} s): {}\n", d.event, d.at_s, *d.detected_s,
                   *d.detected_s - d.at_s, d.explanation);
      else
        fmt::print("event {}    at {:.3f} s: not detected\n", d.event, d.at_s);
    }
    for (const auto& c : checks)
      if (!c.passed) fmt::print("FAILED     {}: {}\n", c.name, c.detail);
    fmt::print("verdict    {} ({} checks, {} failed)\n", failed ? "FAILED" : "PASSED", checks.size(), failed);
    fmt::print("report     {}/report.html (and report.md, alarms.csv, estimates.csv, summary.json)\n", opt->out);
    if (failed) set_exit(1);
  });
}

}  // namespace gpm::cli
