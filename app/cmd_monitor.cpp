// gpm monitor SCENARIO.yaml -o DIR [--model CALIBRATED.yaml] [--hardware HW.yaml]:
// the robot's normal job (scenario `operation:`) on the twin, with `events:`
// changing the actual mechanism, or through hw/ (twin backend or drives), and
// the drift monitor in the servo loop (starting from the 1-sigma of a
// calibration result given as the model); writes
// DIR/alarms.csv, estimates.csv, summary.json and report.md/html
// (run/monitor_run.hpp). Bad input exits 2 with one line. Through hardware,
// DIR and the record (alarms.csv, estimates.csv) are opened before the robot
// moves and written as the monitor records; what was recorded is kept when
// the rest cannot be written, the hardware stops or a signal interrupts.
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "app/cli_text.hpp"
#include "app/commands.hpp"
#include "app/data_files.hpp"
#include "app/progress_mode.hpp"
#include "app/written_files.hpp"
#include "calib/result_yaml.hpp"
#include "models/errors.hpp"
#include "models/output_file.hpp"
#include "models/robot_yaml.hpp"
#include "models/yaml_util.hpp"
#include "hw/hw_errors.hpp"
#include "hw/procedures/stop_on_signal.hpp"
#include "run/monitor_run.hpp"
#include "sim/twin.hpp"

namespace gpm::cli {
namespace {

struct MonitorOptions {
  std::string scenario;
  std::string out;
  std::string model;
  std::string hardware;
  std::string progress;  // --progress (app/progress_mode.hpp)
};

// The monitor's starting 1-sigma per parameter: a calibration result's, NaN where unknown.
std::array<double, kNumParams> prior_sigma(const Robot& controller) {
  std::array<double, kNumParams> prior;
  prior.fill(std::numeric_limits<double>::quiet_NaN());
  if (controller.calibration)
    for (int k = 0; k < kNumParams; ++k) {
      const auto& sd = controller.calibration->sigma[static_cast<std::size_t>(k)];
      if (sd && std::isfinite(*sd) && *sd > 0.0) prior[static_cast<std::size_t>(k)] = *sd;
    }
  return prior;
}

// What the monitor assumes of the readings and where it was stated.
struct ReadingChoice {
  scenario::MonitorReadingModel model;
  std::string from;
};

// A calibration result's `monitor:` (gpm run writes the calibration's
// estimates there), else the scenario's statement (`monitor:`), whose preset
// data_sheet is the robot's data sheet: the model's where it states one (a
// result file does not), else the scenario's robot's.
ReadingChoice reading_of(const MonitorOptions& opt, const sim::Scenario& s, const Robot& controller) {
  const DataSheet& sheet = !opt.model.empty() && load_yaml_file(opt.model)["data_sheet"] ? controller.data_sheet
                                                                                         : s.controller.data_sheet;
  const YAML::Node stated = load_yaml_file(opt.scenario)["monitor"];
  ReadingChoice r{scenario::parse_monitor_reading_model(stated, opt.scenario, sheet),
                  stated ? fmt::format("as stated under monitor: in {}", opt.scenario)
                         : "from the robot's data sheet (the default; a scenario states its own under monitor:)"};
  if (!opt.model.empty())
    if (const YAML::Node n = load_yaml_file(opt.model)["monitor"]) {
      r.model = scenario::parse_monitor_reading_model(n, opt.model, sheet);
      r.from = fmt::format("as the calibration estimated it (monitor: in {})", opt.model);
    }
  return r;
}

// The files of what the monitor records (its alarms, its estimates): through
// hardware they are written as the rows come, and kept when the rest cannot be.
const std::vector<std::string> kRecordNames{"alarms.csv", "estimates.csv"};

// The monitor's record through hardware, alarms.csv and estimates.csv, written
// into the output folder's stage as it is recorded, each row flushed to the
// disk: what was monitored outlives a report that cannot be written, a full
// disk or an interruption (the folder then commits these two alone).
class MonitorLog {
 public:
  // Opens both files in folder's stage (dir names them in messages); throws
  // InputError naming a file that cannot be created.
  MonitorLog(OutputFolder& folder, const std::string& dir) {
    for (size_t k = 0; k < files_.size(); ++k) {
      File& f = files_[k];
      f.shown = (std::filesystem::path(dir) / kRecordNames[k]).string();
      const std::string path = folder.staged_path(kRecordNames[k]);
      f.fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
      if (f.fd < 0) throw InputError(fmt::format("{}: cannot write: {}", f.shown, std::strerror(errno)));
    }
  }
  ~MonitorLog() {
    for (File& f : files_)
      if (f.fd >= 0) ::close(f.fd);
  }
  MonitorLog(const MonitorLog&) = delete;
  MonitorLog& operator=(const MonitorLog&) = delete;

  // Writes the rows of o not written yet (the headers the first time), then
  // flushes both files to the disk. The first call throws InputError naming
  // the file that cannot be written (before anything moves); a later failure
  // ends the writing and is kept (error()).
  void record(const scenario::MonitorOutcome& o) {
    if (!error_.empty()) return;
    std::array<std::string, 2> text;
    if (!started_) text = {scenario::monitor_alarms_header(), scenario::monitor_estimates_header(o)};
    for (; files_[0].rows < o.alarms.size(); ++files_[0].rows) text[0] += scenario::monitor_alarm_row(o.alarms[files_[0].rows]);
    for (; files_[1].rows < o.estimates.size(); ++files_[1].rows)
      text[1] += scenario::monitor_estimate_row(o, o.estimates[files_[1].rows]);
    for (size_t k = 0; k < files_.size() && error_.empty(); ++k) write(files_[k], text[k]);
    if (!started_ && !error_.empty()) throw InputError(fmt::format("{} (nothing moved)", error_));
    started_ = true;
  }
  // Why writing ended early (empty: every row recorded is written).
  const std::string& error() const { return error_; }

 private:
  struct File {
    std::string shown;  // DIR/NAME
    int fd = -1;
    size_t rows = 0;    // rows taken from the outcome
  };
  // Appends text to f whole and flushes it to the disk; keeps the reason on failure.
  void write(File& f, const std::string& text) {
    size_t done = 0;
    while (done < text.size() && error_.empty()) {
      const ssize_t n = ::write(f.fd, text.data() + done, text.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) error_ = fmt::format("{}: write failed: {}", f.shown, std::strerror(errno));
      else done += static_cast<size_t>(n);
    }
    if (error_.empty() && !text.empty() && ::fsync(f.fd) != 0)
      error_ = fmt::format("{}: fsync failed: {}", f.shown, std::strerror(errno));
  }

  std::array<File, 2> files_{};
  bool started_ = false;
  std::string error_;
};

// The number of rows (lines after the header) of a staged file.
size_t rows_in(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  size_t lines = 0;
  for (std::string line; std::getline(in, line);) ++lines;
  return lines > 0 ? lines - 1 : 0;
}

// Moves what was recorded (alarms.csv, estimates.csv) alone into DIR when the
// monitor's other files cannot be written, and removes a previous run's
// summary and report there (DIR never mixes two runs); returns the sentence
// that says what is kept.
std::string keep_record(OutputFolder& folder, const std::string& dir) {
  const size_t alarms = rows_in(folder.staged_path("alarms.csv"));
  const size_t estimates = rows_in(folder.staged_path("estimates.csv"));
  folder.keep_only(kRecordNames);
  folder.commit();
  for (const std::string& name : scenario::monitor_output_names()) {
    const std::filesystem::path p = std::filesystem::path(dir) / name;
    std::error_code ec;
    if (std::find(kRecordNames.begin(), kRecordNames.end(), name) == kRecordNames.end() &&
        std::filesystem::is_regular_file(std::filesystem::symlink_status(p, ec)))
      std::filesystem::remove(p, ec);
  }
  return fmt::format("{} estimates and {} alarm{} kept in {}/estimates.csv and alarms.csv (no summary or report)",
                     estimates, alarms, alarms == 1 ? "" : "s", dir);
}

// The operation on the twin or through the hardware file (its record into
// log as it comes); none when a signal interrupted it (drives disabled, what
// was recorded kept, one line on stderr, exit code 130 set).
std::optional<scenario::MonitorOutcome> run_operation(const MonitorOptions& opt, const sim::Scenario& s,
                                                      const Robot& controller,
                                                      const std::array<double, kNumParams>& prior,
                                                      const scenario::MonitorReadingModel& reading,
                                                      OutputFolder& folder, MonitorLog* log) {
  // Progress on stderr (--progress; app/progress_mode.hpp).
  const auto status = StatusReporter::on_stderr("gpm monitor", progress_mode(opt.progress));
  const auto progress = [&status](double t, double T) {
    status->update(fmt::format("{:.0f} of {:.0f} s of operation", t, T));
  };
  try {
    std::optional<scenario::MonitorOutcome> o;
    if (opt.hardware.empty()) {
      o = scenario::run_monitor(s, controller, prior, reading, progress);
    } else {
      // A robot that moves: drives disabled on SIGINT/SIGTERM/SIGHUP (exit 130).
      const hw::StopOnSignal signals;
      const scenario::MonitorRecord record = [log](const scenario::MonitorOutcome& so_far) { log->record(so_far); };
      try {
        o = scenario::run_monitor_hardware(s, opt.hardware, controller, prior, reading, progress, signals.flag(),
                                           hw::steady_clock(), record);
      } catch (const hw::HardwareError& e) {  // drives disabled: what was recorded is kept
        status->finish();
        const bool interrupted = dynamic_cast<const hw::Interrupted*>(&e) != nullptr;
        const std::string why = interrupted ? fmt::format("{}: {}", hw::StopOnSignal::signal_name(), e.what())
                                            : fmt::format("error: {}", e.what());
        std::fprintf(stderr, "gpm monitor: %s (drives disabled; %s)\n", why.c_str(), keep_record(folder, opt.out).c_str());
        set_exit(interrupted ? hw::kInterruptedExit : 1);
        return std::nullopt;
      }
    }
    status->finish();
    return o;
  } catch (const sim::SimError& e) {
    throw InputError(fmt::format("{}: {}", opt.scenario, e.what()));
  }
}

// Prints the alarms and the events' detections.
void print_alarms(const scenario::MonitorOutcome& o) {
  if (o.truth_known)
    fmt::print("alarms     {} ({} false; stated rate {} per hour)\n", o.alarms.size(), o.false_alarms,
               o.model.settings.false_alarms_per_hour);
  else
    fmt::print("alarms     {} (stated false-alarm rate {} per hour)\n", o.alarms.size(),
               o.model.settings.false_alarms_per_hour);
  for (const auto& a : o.alarms)
    fmt::print("alarm      at {:.3f} s ({} {:.1f} > {:.1f}): {}\n", a.t_s, a.kind, a.statistic, a.threshold,
               terminal_text(a.explanation));
  for (const auto& d : o.detections) {
    if (d.detected_s)
      fmt::print("event {}    at {:.3f} s detected at {:.3f} s (delay {:.3f} s): {}\n", d.event, d.at_s,
                 *d.detected_s, *d.detected_s - d.at_s, terminal_text(d.explanation));
    else
      fmt::print("event {}    at {:.3f} s: not detected\n", d.event, d.at_s);
  }
}

// Prints the run's summary and verdict; exit code 1 when an expectation failed.
void print_summary(const MonitorOptions& opt, const sim::Scenario& s, const scenario::MonitorOutcome& o,
                   const std::string& reading_from, const std::vector<scenario::MonitorCheck>& checks) {
  int failed = 0;
  for (const auto& c : checks) failed += c.passed ? 0 : 1;
  fmt::print("scenario   {} ({})\n", s.name, opt.scenario);
  fmt::print("operation  {:.1f} s, {} servo cycles, {:.1f} s wall\n", o.simulated_s, o.cycles, o.wall_s);
  if (!o.hardware.empty()) fmt::print("hardware   {}\n", o.hardware);
  fmt::print("readings   noise model {}\n", reading_from);
  fmt::print("learning   {}\n", terminal_text(scenario::learning_text(o)));
  print_alarms(o);
  for (const auto& c : checks)
    if (!c.passed) fmt::print("FAILED     {}: {}\n", c.name, terminal_text(c.detail));
  fmt::print("verdict    {} ({} checks, {} failed)\n", failed ? "FAILED" : "PASSED", checks.size(), failed);
  print_written(opt.out);  // report.html, report.md, alarms.csv, estimates.csv, summary.json, figures
  if (failed) set_exit(1);
}

// Writes the outcome's files into DIR (the record again only when its log
// stopped early); true when all were written. When they cannot be (a full
// disk), what was recorded through hardware is kept alone (keep_record), one
// line on stderr says why and what is kept, exit code 1; false.
bool write_outputs(const MonitorOptions& opt, const scenario::MonitorOutcome& o, OutputFolder& folder,
                   const MonitorLog* log) {
  try {
    scenario::stage_monitor(o, folder, !log || !log->error().empty());
    folder.commit();
    return true;
  } catch (const InputError& e) {
    if (!log) throw;
    std::fprintf(stderr, "gpm monitor: error: %s; %s\n", e.what(), keep_record(folder, opt.out).c_str());
    set_exit(1);
    return false;
  }
}

// gpm monitor: the operation with the drift monitor, its files and summary.
void run_monitor_command(const MonitorOptions& opt) {
  // DIR's files against every input (scenario, the files it names, model,
  // hardware file) and not a hardware session's folder: before anything is read.
  check_output_folder(opt.out, scenario::monitor_output_names());
  sim::Scenario s = sim::load_scenario(opt.scenario);
  Robot controller = s.controller;
  if (!opt.model.empty()) controller = load_robot(opt.model);
  // A calibration result as the model: the monitor starts from its 1-sigma.
  const std::array<double, kNumParams> prior = prior_sigma(controller);
  const scenario::MonitorExpect expect = scenario::load_monitor_expect(opt.scenario);  // bad keys before moving
  const ReadingChoice reading = reading_of(opt, s, controller);
  // DIR made and its record opened before anything moves: a folder that
  // cannot be written is refused here (exit 2), not after the operation.
  OutputFolder folder(opt.out, {opt.scenario});
  std::optional<MonitorLog> log;
  if (!opt.hardware.empty()) log.emplace(folder, opt.out);
  const std::optional<scenario::MonitorOutcome> o =
      run_operation(opt, s, controller, prior, reading.model, folder, log ? &*log : nullptr);
  if (!o) return;
  if (!write_outputs(opt, *o, folder, log ? &*log : nullptr)) return;
  print_summary(opt, s, *o, reading.from, scenario::check_monitor(*o, expect));
}

}  // namespace

void add_monitor(CLI::App& app) {
  auto opt = std::make_shared<MonitorOptions>();
  auto* cmd = app.add_subcommand(
      "monitor", "Drift monitoring in normal operation: alarms (what changed, when) and tracked parameters");
  cmd->add_option("scenario", opt->scenario, "Scenario with operation: (and events:): a YAML file, or a name from the scenario library (gpm help scenarios); its keys: gpm help schema")
      ->required();
  cmd->add_option("-o,--out", opt->out, "Output folder: alarms.csv, estimates.csv, summary.json, report.md")->required();
  cmd->add_option("--model", opt->model, "The controller's model (robot or calibration result file); default: the scenario's robot");
  cmd->add_option("--hardware", opt->hardware,
                  "Hardware file (gpm help hardware): monitor the operation through the robot interface (backend twin, modbus or plugin)");
  add_progress_option(cmd, opt->progress);
  cmd->callback([opt] {
    opt->scenario = resolve_scenario(opt->scenario);  // a file, or a library name
    run_monitor_command(*opt);
  });
}

}  // namespace gpm::cli
