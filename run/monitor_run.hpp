// `gpm monitor`: the robot's normal job (scenario `operation:`) on the twin
// through its backend or on the drives (one loop over hw::RobotHardware),
// with the scenario's `events:` changing the actual mechanism, and the drift
// monitor of calib/monitor/ reading the three encoders every servo cycle
// (change test with explained alarms, drift tracking of the parameters).
#pragma once

#include <array>
#include <atomic>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "calib/monitor/monitor.hpp"
#include "models/output_file.hpp"
#include "hw/clock.hpp"
#include "models/robot.hpp"
#include "report/report_document.hpp"
#include "run/run_spec.hpp"
#include "sim/scenario.hpp"

namespace gpm::scenario {

// One row of alarms.csv (an explained alarm).
struct MonitorAlarm {
  double t_s = 0.0;
  std::string kind;  // chi_square or step
  double statistic = 0.0, threshold = 0.0;
  std::string explanation;
  int param = -1;
  double delta = 0.0;
};

// One row of estimates.csv.
struct MonitorEstimateRow {
  double t_s = 0.0;
  std::array<double, kNumParams> value{}, sigma{};
  std::optional<Geometry> truth;  // the actual geometry at t_s in the monitor's gauge (twin only)
};

// How each event of the scenario was detected.
struct MonitorDetection {
  int event = 0;                      // index in the scenario's events
  double at_s = 0.0;                  // when it began
  std::optional<double> detected_s;   // time of the first alarm it explains (none: missed)
  std::string explanation;
};

struct MonitorOutcome {
  std::string scenario_file;
  sim::Scenario scenario;
  Robot controller;  // the model the monitor starts from
  Robot actual;      // the actual mechanism at t = 0
  MonitorReadingModel reading;  // what the monitor assumed of the readings
  calib::monitor::MonitorModel model;
  std::vector<MonitorAlarm> alarms;
  std::vector<MonitorEstimateRow> estimates;
  std::vector<MonitorDetection> detections;
  int false_alarms = 0;                    // alarms no event explains
  // The learning phase (calib/monitor/learning.hpp): when it ended (operation
  // time; no alarm before) and what the monitor learnt of its innovations.
  double learning_start_s = 0.0, learning_end_s = 0.0;
  calib::monitor::LearnedScale learned;
  double chi_threshold = 0.0, step_threshold = 0.0;  // thresholds in force after learning
  // The actual geometry at the end (events and thermal growth), expressed in
  // the monitor's gauge (the similarity that keeps the fixed xa1 ya1 xa2 ya2
  // where the monitor holds them: encoders cannot see the rest).
  Geometry final_truth;
  calib::monitor::Estimate final_estimate;
  double simulated_s = 0.0, wall_s = 0.0;
  long cycles = 0;
  long unmapped = 0;           // samples after learning off the configuration map (not tested)
  int relearnings = 0;         // learning phases begun again because the job left the map
  long accepted = 0;           // samples the monitor used (independence gate, calib/monitor/README.md)
  bool truth_known = true;     // false through hardware: no detections, no final errors
  std::string hardware;        // the backend monitored through (empty: the in-process twin)
};

// An alarm counts as detecting the latest event begun at most this long
// before it (plus the event's ramp time); any other alarm is a false alarm.
inline constexpr double kDetectionWindowS = 10.0;

using MonitorProgress = std::function<void(double t_s, double duration_s)>;

// The outcome so far, as the monitor records it through hardware: called once
// before anything moves (it may throw InputError then: nothing has moved),
// then after each alarm or estimate is added (it must not throw), the last
// time with the final estimate (gpm monitor writes the rows to its output
// folder as they come: nothing monitored is lost to a report that cannot be
// written afterwards).
using MonitorRecord = std::function<void(const MonitorOutcome& so_far)>;

// Runs the scenario's operation on the twin with the monitor in the loop:
// the loop of run_monitor_hardware through the scenario's twin backend
// (run/twin_hardware.hpp), the twin assembled at the path's start, its
// events and growth in the robot's time, the truth from the twin. controller: the model the robot runs (and the monitor starts from);
// prior_sigma: its 1-sigma per parameter (NaN: the monitor's defaults);
// reading: what the monitor assumes of the readings (the scenario's
// `monitor:` statement, or reading_model_after_calibration); the twin's
// `effects:` are the simulated truth and are not read for it.
// Throws InputError when the scenario has no operation, or when an event
// leaves a mechanism that cannot reach the operation path.
MonitorOutcome run_monitor(const sim::Scenario& scenario, const Robot& controller,
                           const std::array<double, kNumParams>& prior_sigma, const MonitorReadingModel& reading,
                           const MonitorProgress& progress = {});

// The same through hardware (hw/: the twin backend, or the drives): the file
// hardware_file (hw/hardware_config.hpp) chooses the backend and its rate;
// the robot moves to the start of the operation path, then follows it for
// duration_s under the hardware's safety supervisor while the monitor reads
// every cycle (readings, speeds and torques as the drives report them) with
// the reading model `reading`. The
// actual mechanism is unknown here: detections and final errors are left
// out (truth_known false). stop (optional) is polled every cycle: a request
// disables the drives and throws hw::Interrupted with what was monitored so far
// kept as far as record kept it. InputError for a bad file, a path outside
// the safety limits or a record that cannot be written, before anything
// moves. clock: the time of the hardware loop (tests share a ManualClock with
// the drive emulator). record (optional): see MonitorRecord.
MonitorOutcome run_monitor_hardware(const sim::Scenario& scenario, const std::string& hardware_file,
                                    const Robot& controller, const std::array<double, kNumParams>& prior_sigma,
                                    const MonitorReadingModel& reading, const MonitorProgress& progress = {},
                                    const std::atomic<bool>* stop = nullptr, hw::Clock& clock = hw::steady_clock(),
                                    const MonitorRecord& record = {});

// Sets the monitor's reading model (skew, compliance, motor-side friction,
// cyclic encoder error, pin clearance, thermal time constant, learning phase
// and least innovation scale) from `reading`.
void apply_reading_model(calib::monitor::MonitorSettings& settings, const MonitorReadingModel& reading);

// The scenario's `expect:` for gpm monitor (every key optional).
struct MonitorExpect {
  std::optional<double> detection_delay_s_max;    // every event detected within this delay
  std::optional<int> false_alarms_max;            // at most this many alarms no event explains
  std::optional<double> final_error_um_max;       // every tracked parameter within this at the end
                                                  // (um; offsets at their active link's tip)
  std::optional<double> tracking_error_um_max;    // ... and at every estimate from tracking_after_s on
  double tracking_after_s = 10.0;
  std::optional<std::string> explanation_contains;  // every detection's explanation contains this
};

// Reads `expect:` of a monitor scenario file; throws InputError naming the key.
MonitorExpect load_monitor_expect(const std::string& scenario_file);

// The checks of expect on a finished run: (name, passed, detail).
struct MonitorCheck {
  std::string name;
  bool passed = true;
  std::string detail;
};
std::vector<MonitorCheck> check_monitor(const MonitorOutcome& outcome, const MonitorExpect& expect);

// Writes DIR/alarms.csv, estimates.csv, summary.json and report.md, all or nothing.
void write_monitor(const MonitorOutcome& outcome, const std::string& dir);
// Stages write_monitor's files in folder (alarms.csv and estimates.csv only
// with_record: a caller that wrote them as they came leaves them); the caller commits.
void stage_monitor(const MonitorOutcome& outcome, OutputFolder& folder, bool with_record = true);
// The files write_monitor writes into DIR (for the check of DIR against
// every input before the run: check_output_folder).
const std::vector<std::string>& monitor_output_names();

// The rows of alarms.csv and estimates.csv, one at a time (each ends in a
// newline): the headers, and one alarm's or estimate's row (the parameters
// o's monitor estimates).
std::string monitor_alarms_header();
std::string monitor_alarm_row(const MonitorAlarm& alarm);
std::string monitor_estimates_header(const MonitorOutcome& o);
std::string monitor_estimate_row(const MonitorOutcome& o, const MonitorEstimateRow& row);

// The parts of write_monitor's output, for gpm run: alarms.csv
// (t_s,kind,statistic,threshold,explanation), estimates.csv (t_s, then each
// estimated parameter and its std), the summary (alarms, false_alarms,
// detections, final_error, ...) and the report section (headings at `level`,
// the parameter-track figure named `figure`).
std::string monitor_alarms_csv(const MonitorOutcome& outcome);
std::string monitor_estimates_csv(const MonitorOutcome& outcome);
nlohmann::json monitor_summary(const MonitorOutcome& outcome);
// The learning phase: summary.json's `learning` block, and one line of text
// (terminal, report).
nlohmann::json learning_summary(const MonitorOutcome& outcome);
std::string learning_text(const MonitorOutcome& outcome);
void add_monitor_section(report::ReportDocument& doc, const MonitorOutcome& outcome, int level,
                         const std::string& figure);

struct RunOutcome;  // run/runner.hpp

// The reading model of gpm run's monitor: what the calibration estimated
// where it made an estimate (latch skew s2, s3 and the compliance of each
// driven joint from a calibration with motion corrections; the joint play d_i
// of the passive links, as pin clearance d_i / 2, zero when the calibration
// looked for it and found none; the drives' friction times the factor the
// model test chose, when it chose one), the scenario's `monitor:` statement
// for the rest (its least innovation scale included: the calibration's misfit
// does not raise it).
MonitorReadingModel reading_model_after_calibration(const RunOutcome& run);

// gpm run's hook: when the scenario has `operation:`, the calibrated model
// (the calibration's geometry, its 1-sigma as the monitor's prior, and the
// reading model of reading_model_after_calibration) monitors the operation
// on the twin; none without operation, or when the run went through
// hardware (gpm monitor --hardware does that).
std::optional<MonitorOutcome> monitor_after_calibration(const RunOutcome& run);

}  // namespace gpm::scenario
