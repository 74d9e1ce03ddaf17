// `gpm monitor` (run/monitor_run.hpp).
#include "run/monitor_run.hpp"

#include <algorithm>
#include <chrono>
#include <memory>
#include <numbers>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "models/errors.hpp"
#include "models/rng.hpp"
#include "models/kinematics.hpp"
#include "models/mjcf.hpp"
#include "models/output_file.hpp"
#include "models/yaml_util.hpp"
#include "hw/hardware_config.hpp"
#include "hw/procedures/motion.hpp"
#include "report/report_document.hpp"
#include "run/runner.hpp"
#include "run/monitor_report_data.hpp"
#include "run/twin_hardware.hpp"
#include "sim/sampling.hpp"
#include "sim/trajectory.hpp"
#include "sim/twin.hpp"

namespace gpm::scenario {
namespace {

// Refuses events that leave a mechanism unable to follow the operation path.
void check_events_assemble(const sim::Scenario& s, const Robot& controller, const Robot& actual) {
  const sim::Path& path = s.operation->path;
  Robot after = actual;
  after.geometry = sim::geometry_after(actual.geometry, s.twin.events);
  if (s.twin.effects.thermal.on())  // links and base plate, each by its own law
    after.geometry = sim::thermal_geometry_at(after.geometry, s.twin.effects.thermal, s.operation->duration_s);
  for (int k = 0; k <= 200; ++k) {
    const Eigen::Vector2d p = sim::path_at(path, sim::path_duration(path) * k / 200.0).p;
    const std::array<std::pair<const Robot*, const char*>, 3> robots{
        {{&controller, "the controller's model"}, {&actual, "the actual mechanism"}, {&after, "the mechanism after the events"}}};
    for (const auto& [robot, what] : robots) {
      const Reach r = check_reach(*robot, p);
      if (!r.ok)
        throw InputError(fmt::format("{}: operation.path: point ({:.3f}, {:.3f}) on {}: {}", s.file, p.x(), p.y(),
                                     what, r.reason));
    }
  }
}

// The truth in the monitor's gauge: encoder readings cannot observe a planar
// similarity of the whole mechanism, so a truth whose fixed coordinates (A1,
// A2) moved (thermal growth of the base plate, an event on them) is mapped by
// the similarity that puts A1 and A2 back where the monitor holds them:
// lengths scale by s, base joints move with the similarity, offsets turn by
// its rotation (every link angle turns by it while the readings do not).
Geometry in_gauge(const Geometry& truth, const Geometry& held) {
  const Eigen::Vector2d a1t(truth[kXa1], truth[kYa1]), a2t(truth[kXa2], truth[kYa2]);
  const Eigen::Vector2d a1h(held[kXa1], held[kYa1]), a2h(held[kXa2], held[kYa2]);
  const Eigen::Vector2d dt = a2t - a1t, dh = a2h - a1h;
  const double scale = dh.norm() / dt.norm();
  const double rot = std::atan2(dh.y(), dh.x()) - std::atan2(dt.y(), dt.x());
  const Eigen::Matrix2d R = Eigen::Rotation2Dd(rot).toRotationMatrix();
  Geometry g = truth;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d a(truth[xa(i)], truth[ya(i)]);
    const Eigen::Vector2d b = a1h + scale * R * (a - a1t);
    g[xa(i)] = b.x();
    g[ya(i)] = b.y();
    g[la(i)] = scale * truth[la(i)];
    g[lb(i)] = scale * truth[lb(i)];
    g[dth(i)] = truth[dth(i)] + rot;
  }
  return g;
}

std::string csv_field(const std::string& s) {
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace

void apply_reading_model(calib::monitor::MonitorSettings& ms, const MonitorReadingModel& reading) {
  const int bits = ms.reading.encoder_bits;  // the encoder is the run's, not the statement's
  const double noise = ms.reading.noise_rad;
  ms.reading = reading.reading;
  ms.reading.encoder_bits = bits;
  ms.reading.noise_rad = noise;
  // A uniform expansion of links and base plate is a similarity, which the
  // encoders cannot see (and the monitor need not track); what they see is
  // the links growing relative to the base, which the monitor's growth state
  // follows on this time constant.
  ms.thermal_tau_s = reading.thermal_time_constant_s;
  ms.learning_s = reading.learning_s;
  ms.scale_floor = reading.scale_floor;
  ms.map_radius_rad = reading.map_radius_rad;
}

namespace {

namespace mon = calib::monitor;

// The outcome's description of the run (scenario and the controller's model), before it starts.
MonitorOutcome outcome_of(const sim::Scenario& s, const Robot& controller) {
  if (!s.operation)
    throw InputError(fmt::format("{}: gpm monitor needs an 'operation' section (the robot's normal job)", s.file));
  MonitorOutcome out;
  out.scenario_file = s.file;
  out.scenario = s;
  out.controller = controller;
  return out;
}

// Makes the outcome's monitor: the controller's model with its 1-sigma, the
// scenario's encoder, read at cycle_hz, the reading model `reading`.
void make_monitor(MonitorOutcome& out, const sim::Scenario& s, const std::array<double, kNumParams>& prior_sigma,
                  double cycle_hz, const MonitorReadingModel& reading) {
  mon::MonitorSettings ms;
  ms.geometry = out.controller.geometry;
  ms.prior_sigma = prior_sigma;
  ms.reading.encoder_bits = s.twin.encoder.bits;
  ms.reading.noise_rad = s.twin.encoder.noise_rad;
  ms.cycle_hz = cycle_hz;
  // At most 200 samples per second whatever the servo rate (the independence
  // gate of calib/monitor/README.md: closer samples share quantisation errors).
  ms.decimation = std::max(1, static_cast<int>(std::lround(ms.cycle_hz / 200.0)));
  apply_reading_model(ms, reading);
  out.reading = reading;
  out.model = mon::make_monitor_model(ms);
}

// When a monitoring loop records an estimate (every `every` s from 0) and
// reports its progress (every second from 1 s).
struct Cadence {
  double every = 0.1;
  double next_estimate = 0.0, next_progress = 1.0;
  // True (once) when an estimate is due at time t.
  bool estimate_due(double t) {
    if (t < next_estimate) return false;
    next_estimate += every;
    return true;
  }
  // True (once) when progress is due at time t.
  bool progress_due(double t) {
    if (t < next_progress) return false;
    next_progress += 1.0;
    return true;
  }
};

// Adds the monitor's last alarm to the outcome when the step r explained one;
// true when it did.
bool take_alarm(MonitorOutcome& out, const mon::MonitorData& md, const mon::StepResult& r) {
  if (!r.explained) return false;
  const mon::Alarm& a = mon::last_alarm(md);
  out.alarms.push_back(
      {a.t_s, mon::alarm_kind_name(a.kind), a.statistic, a.threshold, mon::describe_alarm(a), a.param, a.delta});
  return true;
}

// Flushes the monitor at end_s (the time monitored) and keeps its learning
// phase, thresholds and counts in the outcome.
void close_monitor(MonitorOutcome& out, mon::MonitorData& md, double end_s) {
  mon::monitor_flush(out.model, md);
  out.simulated_s = end_s;
  out.learning_end_s = md.learning ? out.simulated_s : md.learning_end_s;
  out.learned = md.learned;
  out.learning_start_s = md.learning_start_s;
  out.chi_threshold = md.chi_threshold;
  out.step_threshold = md.glr_threshold;
  out.cycles = md.cycles;
  out.accepted = md.accepted;
  out.unmapped = md.unmapped;
  out.relearnings = md.relearnings;
}

// Each alarm detects the latest event begun before it (within the window);
// the others are false alarms.
void match_detections(MonitorOutcome& out, const std::vector<sim::GeometryEvent>& events) {
  for (std::size_t e = 0; e < events.size(); ++e) out.detections.push_back({static_cast<int>(e), events[e].at_s, {}, ""});
  for (const MonitorAlarm& a : out.alarms) {
    int match = -1;
    for (std::size_t e = 0; e < events.size(); ++e)
      if (events[e].at_s <= a.t_s && a.t_s <= events[e].at_s + events[e].over_s + kDetectionWindowS &&
          (match < 0 || events[e].at_s >= events[static_cast<std::size_t>(match)].at_s))
        match = static_cast<int>(e);
    if (match < 0) {
      ++out.false_alarms;
      continue;
    }
    MonitorDetection& d = out.detections[static_cast<std::size_t>(match)];
    if (!d.detected_s) d.detected_s = a.t_s, d.explanation = a.explanation;
  }
}

}  // namespace

MonitorReadingModel reading_model_after_calibration(const RunOutcome& run) {
  MonitorReadingModel m = run.spec.monitor;  // the statement
  if (!run.calibration) return m;
  if (run.reading_estimated) m.reading = *run.reading_estimated;  // the statement with the calibration's estimates
  // The calibration's misfit (its model test's chi2 / dof) is not a floor on
  // the monitor's innovations: it measures what the model leaves over the
  // calibration's poses, while the learning phase's review measures the
  // innovations of this robot's own motion about the filter's estimate
  // (docs/MONITORING.md); the statement's floor stays.
  return m;
}

std::optional<MonitorOutcome> monitor_after_calibration(const RunOutcome& run) {
  const sim::Scenario& s = run.spec.sim;
  if (!s.operation || run.spec.hardware) return std::nullopt;
  std::array<double, kNumParams> prior = mon::MonitorSettings::nan_array();
  if (run.calibration)
    for (int k = 0; k < kNumParams; ++k) {
      const double sd = run.calibration->sigma[static_cast<std::size_t>(k)];
      if (std::isfinite(sd) && sd > 0.0) prior[static_cast<std::size_t>(k)] = sd;
    }
  return run_monitor(s, run.calibrated, prior, reading_model_after_calibration(run));
}

namespace {

// The joint targets along the operation path of s for the controller's model
// (encoder space: theta_a - dth, paper eq. 35), at path time t.
struct JointTargets {
  const sim::Path& path;
  const Robot& controller;
  double loop = 0.0;  // the path's duration (s)

  Eigen::Vector3d operator()(double t) const {
    const Eigen::Vector2d p = sim::path_at(path, std::fmod(t, loop)).p;
    const JointAngles q = inverse_kinematics(controller.geometry, p, controller.branch);
    Eigen::Vector3d m;
    for (int i = 0; i < 3; ++i) m[i] = q.theta_a[i] - controller.geometry.dth_(i);
    return m;
  }
};

// Throws InputError naming the first point of the operation path (of 201 along
// it) the controller's model cannot reach.
void check_path_reach(const sim::Scenario& s, const Robot& controller) {
  const sim::Path& path = s.operation->path;
  for (int k = 0; k <= 200; ++k) {
    const Eigen::Vector2d p = sim::path_at(path, sim::path_duration(path) * k / 200.0).p;
    const Reach r = check_reach(controller, p);
    if (!r.ok)
      throw InputError(fmt::format("{}: operation.path: point ({:.3f}, {:.3f}): {}", s.file, p.x(), p.y(), r.reason));
  }
}

// Every command of the path (a loop and its return to the start, at full
// speed, one per cycle) against the hardware's limits, before anything moves;
// throws InputError naming the scenario, the hardware (where) and why.
void check_path_limits(const hw::SafetySupervisor& robot, const std::array<hw::JointMode, 3>& modes,
                       const JointTargets& target, const sim::Scenario& s, const std::string& where) {
  const double period = robot.period_s();
  const long n = std::lround(std::min(target.loop, s.operation->duration_s) / period) + 3;
  std::vector<Eigen::Vector3d> q;
  q.reserve(static_cast<std::size_t>(n) + 1);
  for (long k = 0; k <= n; ++k) {
    Eigen::Vector3d m = target(static_cast<double>(k) * period);
    if (!q.empty())
      for (int i = 0; i < 3; ++i) m[i] = q.back()[i] + wrap_pi(m[i] - q.back()[i]);
    q.push_back(m);
  }
  const std::string why = robot.check_path(q, modes);
  if (!why.empty())
    throw InputError(fmt::format("{}: operation.path is outside the safety limits of {} (nothing moved): {}", s.file,
                                 where, why));
}

// The path's speed runs in and out over kRunInS (cosine law: no jump in the
// commanded acceleration): the fraction of full speed at robot time tau of total.
constexpr double kRunInS = 1.0;
double run_in_speed(double tau, double total) {
  const double u = std::min({tau, total - tau, kRunInS}) / kRunInS;
  return 0.5 * (1.0 - std::cos(std::numbers::pi * std::max(u, 0.0)));
}

// The actual geometry at a robot time in the monitor's gauge: what only an
// in-process twin knows (empty through hardware).
using TruthAt = std::function<Geometry(double t_s)>;

// The one operation loop of gpm monitor and gpm run, on any hardware (the
// in-process twin is its twin backend): moves the robot to the path's start,
// follows the path for the operation's duration (with the run in and out)
// while the monitor reads every cycle (alarms and estimates into out, with
// truth_at's geometry where given; record called after each), settles and
// shuts the robot down; returns the robot time at the end of the path (s,
// since the procedure started: the twin's own time, which its events use).
// stop: polled every cycle (hw::Interrupted, drives disabled).
double follow_and_monitor(MonitorOutcome& out, mon::MonitorData& md, hw::SafetySupervisor& robot,
                          const std::array<hw::JointMode, 3>& modes, const JointTargets& target, const TruthAt& truth_at,
                          const MonitorProgress& progress, const std::atomic<bool>* stop, const MonitorRecord& record) {
  const double duration = out.scenario.operation->duration_s;
  hw::Motion motion(robot, modes, 0.5, stop);
  motion.start();
  motion.move_joints(motion.wrap_near(target(0.0)), 100.0);
  const double period = robot.period_s();
  const double total = duration + kRunInS;
  const long ticks = std::lround(total / period);
  Cadence cadence{std::max(0.1, total / 2000.0)};
  double t_path = 0.0, t = motion.now();
  for (long k = 0; k <= ticks; ++k) {
    t = motion.now();  // the monitor's time is the robot's
    t_path += run_in_speed(static_cast<double>(k) * period, total) * period;
    motion.cycle(motion.wrap_near(target(t_path)));
    const hw::HardwareState& st = motion.state();
    // Readings polled one after another are carried to one instant first.
    bool recorded = take_alarm(
        out, md, mon::monitor_step(out.model, md, t, hw::readings_at_first_read(st), st.velocity, st.torque));
    if (cadence.estimate_due(t)) {
      const mon::Estimate e = mon::monitor_estimate(out.model, md);
      out.estimates.push_back({t, e.value, e.sigma, truth_at ? std::optional<Geometry>(truth_at(t)) : std::nullopt});
      recorded = true;
    }
    if (recorded && record) record(out);
    if (progress && cadence.progress_due(t)) progress(t, duration);
  }
  motion.settle(sim::SettleCriterion{}, "the end of the operation");
  motion.finish();
  robot.shutdown();
  return t;
}

}  // namespace

MonitorOutcome run_monitor_hardware(const sim::Scenario& s, const std::string& hardware_file, const Robot& controller,
                                    const std::array<double, kNumParams>& prior_sigma, const MonitorReadingModel& reading,
                                    const MonitorProgress& progress, const std::atomic<bool>* stop, hw::Clock& clock,
                                    const MonitorRecord& record) {
  const auto wall0 = std::chrono::steady_clock::now();
  MonitorOutcome out = outcome_of(s, controller);
  if (!s.twin.events.empty())
    throw InputError(fmt::format("{}: events: change the in-process twin only; drop them to monitor through {}", s.file,
                                 hardware_file));
  const hw::HardwareConfig config = hw::load_hardware_config(hardware_file);
  out.actual = controller;
  out.truth_known = false;
  // Every joint target checked against the reach of the controller's model
  // and the hardware's limits, the record opened, before anything moves.
  const JointTargets target{s.operation->path, controller, sim::path_duration(s.operation->path)};
  check_path_reach(s, controller);
  make_monitor(out, s, prior_sigma, config.rate_hz, reading);
  auto md = std::make_unique<mon::MonitorData>(mon::make_monitor_data(out.model));
  std::unique_ptr<hw::SafetySupervisor> robot = hw::make_hardware(config, clock);
  check_path_limits(*robot, config.modes, target, s, hardware_file);
  if (record) record(out);
  out.hardware = robot->describe();
  const double monitored_s = follow_and_monitor(out, *md, *robot, config.modes, target, {}, progress, stop, record);
  close_monitor(out, *md, monitored_s);
  out.final_estimate = mon::monitor_estimate(out.model, *md);
  out.estimates.push_back({out.simulated_s, out.final_estimate.value, out.final_estimate.sigma, std::nullopt});
  if (record) record(out);
  out.final_truth = controller.geometry;
  out.false_alarms = -1;  // unknown: which alarms are real is for the user to find out
  out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return out;
}

MonitorOutcome run_monitor(const sim::Scenario& s, const Robot& controller,
                           const std::array<double, kNumParams>& prior_sigma, const MonitorReadingModel& reading,
                           const MonitorProgress& progress) {
  const auto wall0 = std::chrono::steady_clock::now();
  MonitorOutcome out = outcome_of(s, controller);
  out.actual = sim::make_actual(s);
  check_events_assemble(s, controller, out.actual);
  // The twin (its events and growth in its own time) starts assembled at the
  // start of the operation path, and runs the loop of run_monitor_hardware
  // through its backend (run/twin_hardware.hpp).
  Robot actual_at_start = out.actual, ctrl = controller;
  actual_at_start.home = ctrl.home = sim::path_at(s.operation->path, 0.0).p;
  TwinHardware th = make_twin_hardware(s, actual_at_start, ctrl);
  const std::array<hw::JointMode, 3> modes = twin_joint_modes(s);
  const JointTargets target{s.operation->path, ctrl, sim::path_duration(s.operation->path)};
  make_monitor(out, s, prior_sigma, s.twin.servo_rate_hz, reading);
  auto md = std::make_unique<mon::MonitorData>(mon::make_monitor_data(out.model));
  check_path_limits(*th.robot, modes, target, s, "the twin");
  const sim::TwinModel& twin = th.twin->model(modes);
  const FreeMask gauge = ~default_free_mask();  // xa1 ya1 xa2 ya2
  const bool regauge = (gauge & out.model.settings.estimate).none();
  const TruthAt truth_at = [&](double t) {
    const Geometry g = sim::geometry_at_time(twin, t);
    return regauge ? in_gauge(g, controller.geometry) : g;
  };
  const double monitored_s = follow_and_monitor(out, *md, *th.robot, modes, target, truth_at, progress, nullptr, {});
  close_monitor(out, *md, monitored_s);
  out.final_estimate = mon::monitor_estimate(out.model, *md);
  out.final_truth = truth_at(out.simulated_s);
  out.estimates.push_back({out.simulated_s, out.final_estimate.value, out.final_estimate.sigma, out.final_truth});
  match_detections(out, s.twin.events);
  out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return out;
}

MonitorExpect load_monitor_expect(const std::string& scenario_file) {
  const YAML::Node root = load_yaml_file(scenario_file);
  MonitorExpect e;
  const YAML::Node n = root["expect"];
  if (!n) return e;
  yaml_check_keys(n, scenario_file, "expect",
                  {"detection_delay_s_max", "false_alarms_max", "final_error_um_max", "tracking_error_um_max",
                   "tracking_after_s", "explanation_contains"});
  if (n["detection_delay_s_max"])
    e.detection_delay_s_max = yaml_positive(n["detection_delay_s_max"], scenario_file, "expect.detection_delay_s_max");
  if (n["false_alarms_max"])
    e.false_alarms_max = static_cast<int>(yaml_integer(n["false_alarms_max"], scenario_file, "expect.false_alarms_max", 0, 1000000));
  if (n["final_error_um_max"])
    e.final_error_um_max = yaml_positive(n["final_error_um_max"], scenario_file, "expect.final_error_um_max");
  if (n["tracking_error_um_max"])
    e.tracking_error_um_max = yaml_positive(n["tracking_error_um_max"], scenario_file, "expect.tracking_error_um_max");
  if (n["tracking_after_s"])
    e.tracking_after_s = yaml_positive(n["tracking_after_s"], scenario_file, "expect.tracking_after_s");
  if (n["explanation_contains"])
    e.explanation_contains = yaml_string(n["explanation_contains"], scenario_file, "expect.explanation_contains");
  return e;
}

std::vector<MonitorCheck> check_monitor(const MonitorOutcome& o, const MonitorExpect& e) {
  std::vector<MonitorCheck> out;
  for (const MonitorDetection& d : o.detections) {
    if (e.detection_delay_s_max) {
      const bool ok = d.detected_s && *d.detected_s - d.at_s <= *e.detection_delay_s_max;
      out.push_back({fmt::format("detection.{}", d.event), ok,
                     d.detected_s ? fmt::format("event at {:.3f} s detected after {:.3f} s (limit {:.3g} s)", d.at_s,
                                                *d.detected_s - d.at_s, *e.detection_delay_s_max)
                                  : fmt::format("event at {:.3f} s not detected", d.at_s)});
    }
    if (e.explanation_contains && d.detected_s) {
      const bool ok = d.explanation.find(*e.explanation_contains) != std::string::npos;
      out.push_back({fmt::format("explanation.{}", d.event), ok, d.explanation});
    }
  }
  if (e.false_alarms_max) {
    // Through hardware no alarm is known to be false: all of them count.
    const int n = o.truth_known ? o.false_alarms : static_cast<int>(o.alarms.size());
    out.push_back({"false_alarms", n <= *e.false_alarms_max,
                   fmt::format("{} {}alarms in {:.1f} s (limit {})", n, o.truth_known ? "false " : "", o.simulated_s,
                               *e.false_alarms_max)});
  }
  if (e.tracking_error_um_max && o.truth_known) {
    // The worst error of each tracked parameter over the estimates from tracking_after_s on.
    const FreeMask est = o.model.settings.estimate;
    for (int k = 0; k < kNumParams; ++k) {
      if (!est[static_cast<std::size_t>(k)]) continue;
      const double scale = is_offset(k) ? o.controller.geometry.la_(k - kDth1) * 1e3 : 1e3;
      double worst = 0.0, at = 0.0;
      for (const MonitorEstimateRow& r : o.estimates) {
        if (r.t_s < e.tracking_after_s || !r.truth) continue;
        const double err = std::abs(r.value[static_cast<std::size_t>(k)] - (*r.truth)[k]) * scale;
        if (err > worst) worst = err, at = r.t_s;
      }
      out.push_back({fmt::format("tracking_error.{}", param_name(k)), worst <= *e.tracking_error_um_max,
                     fmt::format("worst {:.3f} um at {:.1f} s from {:.0f} s on (limit {:.3g})", worst, at,
                                 e.tracking_after_s, *e.tracking_error_um_max)});
    }
  }
  if (e.final_error_um_max && o.truth_known) {
    const FreeMask est = o.model.settings.estimate;
    for (int k = 0; k < kNumParams; ++k) {
      if (!est[static_cast<std::size_t>(k)]) continue;
      const double scale = is_offset(k) ? o.controller.geometry.la_(k - kDth1) * 1e3 : 1e3;
      const double err = std::abs(o.final_estimate.value[static_cast<std::size_t>(k)] - o.final_truth.values[static_cast<std::size_t>(k)]) * scale;
      out.push_back({fmt::format("final_error.{}", param_name(k)), err <= *e.final_error_um_max,
                     fmt::format("{:.3f} um (limit {:.3g})", err, *e.final_error_um_max)});
    }
  }
  return out;
}

std::string monitor_alarms_header() { return "t_s,kind,statistic,threshold,explanation\n"; }

std::string monitor_alarm_row(const MonitorAlarm& a) {
  return fmt::format("{:.6f},{},{:.6g},{:.6g},{}\n", a.t_s, a.kind, a.statistic, a.threshold, csv_field(a.explanation));
}

std::string monitor_alarms_csv(const MonitorOutcome& o) {
  std::string alarms = monitor_alarms_header();
  for (const MonitorAlarm& a : o.alarms) alarms += monitor_alarm_row(a);
  return alarms;
}

std::string monitor_estimates_header(const MonitorOutcome& o) {
  const FreeMask est = o.model.settings.estimate;
  std::string header = "t_s";
  for (int k = 0; k < kNumParams; ++k)
    if (est[static_cast<std::size_t>(k)]) header += fmt::format(",{0},{0}_std", param_name(k));
  return header + "\n";
}

std::string monitor_estimate_row(const MonitorOutcome& o, const MonitorEstimateRow& r) {
  const FreeMask est = o.model.settings.estimate;
  std::string row = fmt::format("{:.6f}", r.t_s);
  for (int k = 0; k < kNumParams; ++k)
    if (est[static_cast<std::size_t>(k)])
      row += fmt::format(",{:.12g},{:.6g}", r.value[static_cast<std::size_t>(k)], r.sigma[static_cast<std::size_t>(k)]);
  return row + "\n";
}

std::string monitor_estimates_csv(const MonitorOutcome& o) {
  std::string estimates = monitor_estimates_header(o);
  for (const MonitorEstimateRow& r : o.estimates) estimates += monitor_estimate_row(o, r);
  return estimates;
}

nlohmann::json monitor_summary(const MonitorOutcome& o) {
  const FreeMask est = o.model.settings.estimate;
  nlohmann::json j;
  j["scenario"] = o.scenario_file;
  j["duration_s"] = o.simulated_s;
  j["cycles"] = o.cycles;
  j["samples"] = o.accepted;
  j["alarms"] = o.alarms.size();
  j["false_alarms"] = o.truth_known ? nlohmann::json(o.false_alarms) : nlohmann::json(nullptr);
  if (!o.hardware.empty()) j["hardware"] = o.hardware;
  j["false_alarm_rate_per_hour"] = o.model.settings.false_alarms_per_hour;
  j["learning"] = learning_summary(o);
  // What the monitor assumed of the readings (the statement, or the calibration's estimates).
  const calib::ReadingModel& r = o.reading.reading;
  j["reading_model"] = {{"encoder_cyclic_rad", r.cyclic_rad},
                        {"clearance_mm", calib::pin_clearance_mm(r)},
                        {"coulomb_Nm", r.load.coulomb_Nm},
                        {"viscous_Nm_s", r.load.viscous_Nm_s},
                        {"skew_s", r.skew_s},
                        {"compliance_rad_per_Nm", r.compliance_rad_per_Nm},
                        {"backlash_rad", r.backlash_rad},
                        {"thermal_time_constant_s", o.reading.thermal_time_constant_s}};
  j["detections"] = nlohmann::json::array();
  for (const MonitorDetection& d : o.detections) {
    nlohmann::json dj = {{"event", d.event}, {"at_s", d.at_s}};
    dj["detected_s"] = d.detected_s ? nlohmann::json(*d.detected_s) : nlohmann::json(nullptr);
    dj["delay_s"] = d.detected_s ? nlohmann::json(*d.detected_s - d.at_s) : nlohmann::json(nullptr);
    dj["explanation"] = d.explanation;
    j["detections"].push_back(dj);
  }
  nlohmann::json fe = nlohmann::json::object();
  for (int k = 0; k < kNumParams; ++k)
    if (est[static_cast<std::size_t>(k)] && o.truth_known)
      fe[std::string(param_name(k))] = o.final_estimate.value[static_cast<std::size_t>(k)] - o.final_truth.values[static_cast<std::size_t>(k)];
  j["final_error"] = fe;
  return j;
}

nlohmann::json learning_summary(const MonitorOutcome& o) {
  const calib::monitor::LearnedScale& l = o.learned;
  return {{"learning_s", o.model.settings.learning_s},
          {"length_s", o.learning_end_s - o.learning_start_s},
          {"ended_s", o.learning_end_s},
          {"samples", l.samples},
          {"innovation_median", l.median},
          {"innovation_mad_scale", l.mad_scale},
          {"scale", l.scale},
          {"scale_floor", o.model.settings.scale_floor},
          {"step_factor", l.step_factor},
          {"chi_mean", l.chi_mean},
          {"chi_factor", l.chi_factor},
          {"chi_square_threshold", o.chi_threshold},
          {"step_threshold", o.step_threshold},
          {"map", l.map},
          {"map_matched_samples", l.map_matched},
          {"unmapped_samples", o.unmapped},
          {"relearnings", o.relearnings}};
}

std::string learning_text(const MonitorOutcome& o) {
  const calib::monitor::LearnedScale& l = o.learned;
  if (o.model.settings.learning_s <= 0.0) return "no learning phase (the stated reading model taken as exact)";
  return fmt::format(
      "learning phase {:.2f} s (no alarm before {:.2f} s), {} samples: innovation scale {:.2f} (MAD; {:.2f} used, "
      "floor {:.2f}), bias {:+.2f}; step test divided by up to {:.1f} (threshold {:.1f}), chi2 threshold "
      "{:.1f} (stated {:.1f}); configuration map {} ({} learnt samples matched by another pass, {} later samples "
      "off it, not tested; learnt again {} times where the job left it)",
      o.learning_end_s - o.learning_start_s, o.learning_end_s, l.samples, l.mad_scale, l.scale,
      o.model.settings.scale_floor, l.median, l.step_factor, o.step_threshold, o.chi_threshold, o.model.threshold,
      l.map ? "on" : "off", l.map_matched, o.unmapped, o.relearnings);
}

void add_monitor_section(report::ReportDocument& doc, const MonitorOutcome& o, int level, const std::string& figure) {
  report::add_monitor_section(doc, monitor_report_data(o), level, figure);
}

const std::vector<std::string>& monitor_output_names() {
  static const std::vector<std::string> names{"alarms.csv", "estimates.csv", "summary.json",
                                              "report.md",  "report.html",   "tracks.svg"};
  return names;
}

void stage_monitor(const MonitorOutcome& o, OutputFolder& folder, bool with_record) {
  if (with_record) {
    folder.add("alarms.csv", monitor_alarms_csv(o));
    folder.add("estimates.csv", monitor_estimates_csv(o));
  }
  folder.add("summary.json", monitor_summary(o).dump(2) + "\n");
  report::monitor_report(o.scenario.name, monitor_report_data(o))
      .stage(folder, "report", fmt::format("gpm monitor: {}", o.scenario.name));
}

void write_monitor(const MonitorOutcome& o, const std::string& dir) {
  OutputFolder folder(dir, {o.scenario_file});
  stage_monitor(o, folder);
  folder.commit();
}

}  // namespace gpm::scenario
