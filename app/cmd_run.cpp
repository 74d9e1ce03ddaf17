// gpm run SCENARIO.yaml -o DIR: simulate, calibrate, compensate, evaluate and
// report (run/runner.hpp). Exit 1 when an expectation fails.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "app/cli_text.hpp"
#include "app/commands.hpp"
#include "app/data_files.hpp"
#include "app/progress_mode.hpp"
#include "app/written_files.hpp"
#include "hw/hardware_config.hpp"
#include "hw/hw_errors.hpp"
#include "hw/procedures/stop_on_signal.hpp"
#include "models/errors.hpp"
#include "models/measured_data.hpp"
#include "models/output_file.hpp"
#include "report/run_report.hpp"
#include "report/table_cell.hpp"
#include "run/run_spec.hpp"
#include "run/runner.hpp"
#include "sim/simulate.hpp"

namespace gpm::cli {
namespace {

struct RunOptions {
  std::string scenario;
  std::string out;
  std::string hardware;
  bool quiet = false;
  std::string progress;  // --progress (app/progress_mode.hpp)
  bool resume = false;
};

// The run in one line, as the report's lead says it: the tool tip's static
// error before and after, and the robot time the sampling took.
void print_result(const scenario::RunOutcome& o) {
  if (!o.before || !o.after || o.refused) return;
  const auto distance = [](double v) {
    return std::abs(v) >= 1000.0 ? report::sig(v / 1000.0) + " mm" : report::sig(v) + " " + um();
  };
  fmt::print("result     tool tip {} from where it is sent with the nominal model, {} calibrated ({}x closer){}\n",
             distance(o.before->static_rms_um), distance(o.after->static_rms_um),
             report::ratio_text(o.before->static_rms_um / std::max(1e-12, o.after->static_rms_um)),
             o.hardware_description.empty() ? fmt::format("; sampled in {} s of robot time", report::sig(o.sim.sampling_s, 2))
                                            : std::string());
}

// The accuracy lines: nominal, calibrated and the floor, with calibrated / floor and its interval.
void print_accuracy(const scenario::RunOutcome& o) {
  if (o.before) {
    fmt::print("accuracy   nominal model:    static RMS {:9.2f} {u}, max {:9.2f} {u}; path RMS {:9.2f} {u}\n",
               o.before->static_rms_um, o.before->static_max_um, o.before->path_rms_um, fmt::arg("u", um()));
  }
  if (o.after) {
    fmt::print("           calibrated model: static RMS {:9.2f} {u}, max {:9.2f} {u}; path RMS {:9.2f} {u}\n",
               o.after->static_rms_um, o.after->static_max_um, o.after->path_rms_um, fmt::arg("u", um()));
  }
  if (o.floor) {
    fmt::print("           actual (floor):   static RMS {:9.2f} {u}, max {:9.2f} {u}; path RMS {:9.2f} {u}\n",
               o.floor->static_rms_um, o.floor->static_max_um, o.floor->path_rms_um, fmt::arg("u", um()));
    if (o.floor_ratio_ci95)
      fmt::print("           calibrated / floor {:.2f} (95 % interval {:.2f}-{:.2f} over the {} test poses)\n",
                 o.after->static_rms_um / o.floor->static_rms_um, (*o.floor_ratio_ci95)[0], (*o.floor_ratio_ci95)[1],
                 o.after->static_error_um.size());
  }
}

void print_summary(const scenario::RunOutcome& o, const std::string& dir) {
  fmt::print("scenario   {} ({})\n", o.spec.sim.name, o.scenario_file);
  fmt::print("samples    {} {}\n", o.sim.samples.size(),
             o.hardware_description.empty() ? "from the twin" : "through " + o.hardware_description);
  if (o.first_pass) {
    const scenario::FirstPass& f = *o.first_pass;
    fmt::print("first pass {} ({}); the encoder offsets from its {} samples moved by {:.2e}, {:.2e}, {:.2e} "
               "rad: the path was sampled {} with them\n",
               f.planned ? "as planned" : "ended early", terminal_text(f.why), f.samples, f.offsets_change_rad[0],
               f.offsets_change_rad[1], f.offsets_change_rad[2], f.planned ? "whole" : "a second time");
  }
  if (o.calibration) {
    const auto& r = *o.calibration;
    fmt::print("calibrate  {} on {}: J = {:.4g}, {} iterations, rank {}, cond {:.3g}{}\n", r.method,
               calib::cost_name(r.cost), r.final_cost, r.iterations, r.rank, r.condition_number,
               r.kmrmse_mm ? fmt::format(", kmrmse {:.3g} mm", *r.kmrmse_mm) : "");
    double worst = 0.0;
    std::string worst_name;
    for (int i = 0; i < kNumParams; ++i) {
      if (!r.free.test(static_cast<size_t>(i))) continue;
      const double e = std::abs(r.geometry[i] - o.sim.actual.geometry[i]) * (is_offset(i) ? 244.0 : 1.0);
      if (e >= worst) worst = e, worst_name = std::string(param_name(i));
    }
    fmt::print("errors     largest {}: {:.4f} mm (offsets counted as mm at the 244 mm link)\n", worst_name, worst);
  }
  if (o.refused) fmt::print("refused    {}\n", *o.refused);
  if (o.positioning) {
    fmt::print("position   calibrated model over the 80 mm disc: RMS {:.2f} {u}, max {:.2f} {u} (stated 1-sigma {:.2f} "
               "{u} per axis{}; error / 1-sigma {:.2f}, 1 when honest){}\n",
               o.positioning->rms_um, o.positioning->max_um, o.positioning->stated_sigma_rms_um,
               carried_share(o.positioning->carried_sigma_rms_um), o.positioning->normalised_rms,
               o.positioning_bound_um
                   ? fmt::format("; these readings allow an RMS of {:.2f} {} at best", *o.positioning_bound_um, um())
                   : std::string(),
               fmt::arg("u", um()));
  }
  if (o.stated_positioning)
    fmt::print("position   calibrated model over the 80 mm disc: stated 1-sigma {:.2f} {} per axis{} (its error "
               "needs the truth: known in simulation only)\n",
               o.stated_positioning->stated_sigma_rms_um, um(), carried_share(o.stated_positioning->carried_sigma_rms_um));
  print_accuracy(o);
  if (o.hardware_description.empty())
    fmt::print("robot time {:.2f} s of sampling {} (the time the robot is kept from its work)\n", o.sim.sampling_s,
               o.in_motion ? "on the fly" : "at rest at each pose");
  if (o.model_test) {  // in the report's voice (report::model_test_verdict)
    const report::ModelTestVerdict v = report::model_test_verdict(
        o.model_test->passed, o.model_test->chi2, o.model_test->dof,
        o.positioning ? std::optional<double>(o.positioning->normalised_rms) : std::nullopt);
    const double expected = o.model_test->dof + o.model_test->doubt_chi2;
    const std::string doubt = o.model_test->doubt_chi2 > 0.0
                                  ? fmt::format(" ({:.0f} expected with the doubt where a joint may rest)", expected)
                                  : "";
    fmt::print("model test {} {:.4g} for {:.0f} degrees of freedom{}, p = {:.3g}: {}\n", chi2(), o.model_test->chi2,
               o.model_test->dof, doubt, o.model_test->p_value, report::model_test_verdict_line(v));
  }
  if (o.monitor) {
    const scenario::MonitorOutcome& m = *o.monitor;
    fmt::print("monitor    {:.1f} s of operation, {} ({} false)\n", m.simulated_s, count_of(m.alarms.size(), "alarm"),
               m.false_alarms);
    fmt::print("learning   {}\n", terminal_text(scenario::learning_text(m)));
    for (const auto& d : m.detections)
      fmt::print("event {}    at {:.3f} s {}\n", d.event, d.at_s,
                 d.detected_s ? fmt::format("detected after {:.3f} s: {}", *d.detected_s - d.at_s, terminal_text(d.explanation))
                              : std::string("not detected"));
  }
  size_t failed = 0;
  for (const auto& c : o.checks) {
    if (!c.passed) {
      ++failed;
      fmt::print("FAILED     {}: {}\n", c.name, terminal_text(c.detail));
    }
  }
  print_result(o);
  fmt::print("verdict    {} ({} checks, {} failed) in {:.1f} s\n", failed ? "FAILED" : "PASSED", o.checks.size(),
             failed, o.seconds);
  print_written(dir);  // summary.json, report.html, ...: every file of DIR this run wrote
}

}  // namespace

void add_run(CLI::App& app) {
  auto opt = std::make_shared<RunOptions>();
  auto* cmd = app.add_subcommand(
      "run", "Simulate, calibrate, compensate and report a scenario (exit 1 if an expectation fails); writes DIR/summary.json, "
             "report.html, report.md, calibration.yaml, samples.csv, trajectory.csv, actual.yaml, model.xml and figures "
             "(gpm help formats)");
  cmd->add_option("scenario", opt->scenario, "Scenario: a YAML file, or a name from the scenario library (gpm help scenarios); its keys: gpm help schema")->required();
  cmd->add_option("-o,--out", opt->out, "Output folder")->required();
  cmd->add_option("--hardware", opt->hardware,
                  "Hardware file (gpm help hardware): take the samples through the robot interface (backend twin, modbus or plugin)");
  cmd->add_flag("-q,--quiet", opt->quiet, "No progress on stderr (--progress=none)");
  add_progress_option(cmd, opt->progress);
  cmd->add_flag("--resume", opt->resume, "With --hardware: continue DIR/samples.csv of a stopped run (same plan)");
  cmd->callback([opt] {
    opt->scenario = resolve_scenario(opt->scenario);  // a file, or a library name (gpm run main)
    // Every file DIR gets, against every input the run reads (scenario, the
    // files it names, hardware file): refused before anything is parsed.
    for (const std::string& name : scenario::run_output_names())
      declare_output((std::filesystem::path(opt->out) / name).string());
    scenario::RunSpec spec = scenario::load_run_spec(opt->scenario);
    if (!opt->hardware.empty()) spec.hardware = opt->hardware;
    if (opt->resume && !spec.hardware)
      throw InputError(fmt::format("--resume continues the measured samples of a hardware run: give --hardware "
                                   "HW.yaml (or hardware: in {})",
                                   opt->scenario));
    spec.hardware_resume = opt->resume;
    std::optional<MeasuredFolder> measured;  // models/measured_data.hpp
    if (spec.hardware) {
      // A bad hardware file is refused before the folder is made; then DIR is
      // marked and locked for this session: samples are appended to
      // DIR/samples.csv as they are taken (nothing measured is lost), and no
      // other command writes DIR.
      hw::load_hardware_config(*spec.hardware);
      measured.emplace(opt->out, "gpm run --hardware", "samples.csv");
    } else {
      check_output_folder(opt->out, scenario::run_output_names());  // not a file, no measured folder nor log
    }
    const std::string samples_path = measured ? measured->samples_path() : std::string();
    std::optional<scenario::RunOutcome> ran;
    try {  // a stopped hardware session: drives disabled, samples kept (hw/README.md)
      const auto status = StatusReporter::on_stderr("gpm run", progress_mode(opt->quiet ? "none" : opt->progress));
      const scenario::Progress stages = [&status](const std::string& stage) { status->update(stage); };
      ran = scenario::run_scenario(spec, opt->scenario, stages, samples_path);
    } catch (const hw::HardwareError& e) {
      const bool interrupted = dynamic_cast<const hw::Interrupted*>(&e) != nullptr;
      std::fprintf(stderr, "gpm: %s%s; to go on: gpm run %s -o %s --hardware %s --resume\n",
                   interrupted ? "" : "error: ", e.what(), opt->scenario.c_str(), opt->out.c_str(),
                   spec.hardware->c_str());
      set_exit(interrupted ? hw::kInterruptedExit : 1);
      return;
    } catch (const sim::TrackingStop& e) {
      // The twin's tracking watch stopped the robot: what it measured is kept.
      OutputFolder out(opt->out, {opt->scenario});
      out.add("samples.csv", sim::samples_csv(e.samples));
      sim::TrajectoryLog log;
      log.rows = e.rows;
      out.add("trajectory.csv", sim::trajectory_csv(log));
      out.commit();
      std::fprintf(stderr, "gpm: error: %s; %zu samples kept in %s/samples.csv\n", e.what(), e.samples.size(),
                   opt->out.c_str());
      print_written(opt->out);
      set_exit(1);
      return;
    }
    const scenario::RunOutcome& outcome = *ran;
    scenario::write_run(outcome, opt->out, measured ? &*measured : nullptr);
    print_summary(outcome, opt->out);
    set_exit(outcome.passed() ? 0 : 1);
  });
}

}  // namespace gpm::cli
