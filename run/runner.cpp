#include "run/runner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "calib/identifiability.hpp"
#include "calib/calibrate.hpp"
#include "calib/crb.hpp"
#include "calib/friction_profile.hpp"
#include "calib/model_test.hpp"
#include "calib/motion_correction.hpp"
#include "calib/reading_rates.hpp"
#include "calib/residuals.hpp"
#include "calib/result_yaml.hpp"
#include "models/pose_layouts.hpp"
#include "models/errors.hpp"
#include "models/rng.hpp"
#include "models/kinematics.hpp"
#include "models/output_file.hpp"
#include "hw/hardware_config.hpp"
#include "hw/safety_limits.hpp"
#include "hw/procedures/sample_log.hpp"
#include "hw/procedures/sampling_session.hpp"
#include "hw/procedures/stop_on_signal.hpp"
#include "hw/procedures/trajectory_session.hpp"
#include "models/robot_yaml.hpp"
#include "models/samples.hpp"
#include "run/calibration_inputs.hpp"
#include "run/calibration_procedure.hpp"
#include "run/expectations.hpp"
#include "run/run_report_data.hpp"
#include "run/offsets_first.hpp"
#include "run/sampling_design.hpp"
#include "run/summary_json.hpp"
#include "run/twin_hardware.hpp"

namespace gpm::scenario {

bool RunOutcome::passed() const {
  for (const Check& c : checks)
    if (!c.passed) return false;
  return true;
}

namespace {

// The calibrated model's positioning error over the workspace (nullopt when
// no point of the disc is reachable by it).
std::optional<calib::PositioningError> calibrated_positioning(const RunOutcome& o) {
  try {
    return calib::positioning_error(o.sim.actual, o.calibrated, calib::WorkspaceDisc{o.nominal.home},
                                    o.calibration->covariance, o.calibration->carried_covariance);
  } catch (const InputError&) {
    return std::nullopt;
  }
}

// A Cramer-Rao bound that bound() computes at unit reading noise, scaled to
// sigma (rad; 0 for ideal encoders); NaN in every slot when the information
// is singular (reported as unidentifiable).
template <class Bound>
std::array<double, kNumParams> scaled_bound(Bound&& bound, double sigma) {
  std::array<double, kNumParams> out;
  try {
    out = bound();
    for (double& v : out) v *= sigma;
  } catch (const std::exception&) {
    out.fill(NAN);
  }
  return out;
}

}  // namespace

namespace {

// The scenario's drives as the hardware's joint modes: the trajectory
// procedure runs with the drives its path keeps its margin for (servo.modes).
std::array<hw::JointMode, 3> procedure_modes(const RunSpec& spec, const std::string& scenario_file) {
  std::array<hw::JointMode, 3> modes{};
  for (std::size_t i = 0; i < 3; ++i) {
    const sim::ServoMode m = spec.sim.twin.drives[i].mode;
    if (m == sim::ServoMode::kTorque)
      throw InputError(fmt::format("{}: servo.modes: joint {} in torque mode: the hardware interface drives "
                                   "position or torque_off joints",
                                   scenario_file, i + 1));
    modes[i] = m == sim::ServoMode::kPosition ? hw::JointMode::kPosition : hw::JointMode::kTorqueOff;
  }
  return modes;
}

// The on-the-fly plan: the scenario's excitation path (sim::excitation_plan,
// its margin for the scenario's drives), one sample per sample_every /
// servo.rate_hz seconds or per cycle where the hardware (rate_hz) is slower;
// end_s > 0: only its first end_s seconds (the offsets stage).
hw::TrajectoryPlan trajectory_plan(const RunSpec& spec, double rate_hz, const std::array<hw::JointMode, 3>& modes,
                                   const std::vector<Eigen::Vector2d>& poses, double end_s) {
  hw::TrajectoryPlan plan;
  plan.path = sim::excitation_plan(spec.sim, poses);
  if (end_s > 0.0 && end_s >= sim::waypoint_duration(plan.path))
    throw InputError(fmt::format("{}: sampling.offsets_first_s: {:g} s is not shorter than the excitation path ({:.3g} s): "
                                 "state less, or 0 for none",
                                 spec.sim.file, end_s, sim::waypoint_duration(plan.path)));
  plan.end_s = end_s;
  plan.modes = modes;
  const double interval_s = spec.sim.sampling->sample_every / spec.sim.twin.servo_rate_hz;
  plan.every = std::max(1, static_cast<int>(std::lround(interval_s * rate_hz)));
  plan.move_speed_mm_s = spec.sim.sampling->options.move_speed_mm_s;
  plan.settle = spec.sim.sampling->options.settle;
  return plan;
}

// The stop-and-go plan: the scenario's poses, moves, settling (a pose that
// does not settle within its timeout is sampled as it stands, as the
// scenario's settle criterion states) and averaging.
hw::SessionPlan session_plan(const RunSpec& spec, const std::vector<Eigen::Vector2d>& poses,
                             const std::array<hw::JointMode, 3>& modes, std::optional<double> dither_mm) {
  hw::SessionPlan plan;
  plan.poses = poses;
  plan.options = spec.sim.sampling->options;
  plan.modes = modes;
  if (dither_mm) plan.dither_mm = *dither_mm;
  plan.require_settled = false;  // the scenario's settle timeout gives up the wait (sim::SettleCriterion)
  return plan;
}

// One sample of the file as the runner's record. Through the interface only
// the readings (and on the fly the torques and times) are known; the pose is
// the target, and the true angles those of the scenario's actual robot there.
sim::SampleRecord sample_record(long id, const hw::SampleLog::Recorded& row, const Robot& actual) {
  sim::SampleRecord rec;
  rec.id = id;
  rec.theta_m = row.theta_m;
  rec.target = row.target;
  rec.xy_mm = rec.target;
  rec.theta_a = inverse_kinematics(actual.geometry, rec.target, actual.branch).theta_a;
  rec.settled = !row.motion;
  if (row.motion) {
    rec.t_s = row.motion->t_s;
    rec.tau = row.motion->tau;
    rec.tau_last = row.motion->tau_last;
    rec.tau_between = row.motion->tau_between;
    rec.read_lag_s = Eigen::Vector3d::Constant(row.motion->t_read[0]) - row.motion->t_read;
  }
  return rec;
}

// Samples through the hardware interface (hw/): the scenario's poses, sampled
// stop-and-go (hw/procedures/sampling_session.hpp) or on the fly along the
// excitation path (pattern trajectory: hw/procedures/trajectory_session.hpp),
// every sample on disk as taken; the hardware file's controller with its
// encoder offsets moved by dth_change (rad; a second pass: plan_second_pass).
sim::SimulationResult sample_on_hardware(const RunSpec& spec, const std::string& samples_path,
                                         std::string& description, const Eigen::Vector3d& dth_change,
                                         double end_s = 0.0) {
  if (samples_path.empty()) throw InputError("gpm run --hardware: no output folder for the samples");
  hw::HardwareConfig cfg = hw::load_hardware_config(*spec.hardware);
  for (int i = 0; i < 3; ++i) cfg.controller.geometry[dth(i)] += dth_change[i];
  const std::vector<Eigen::Vector2d> poses = sim::plan_poses(*spec.sim.sampling, spec.sim.seed);
  const bool in_motion = spec.sim.sampling->pattern == sim::PosePattern::kTrajectory;
  sim::SimulationResult r;
  r.actual = sim::make_actual(spec.sim);
  const hw::StopOnSignal signals;  // hw/procedures/stop_on_signal.hpp: drives off, exit 130
  hw::SampleLog log(samples_path, spec.hardware_resume,
                    in_motion ? hw::SampleColumns::kOnTheFly : hw::SampleColumns::kAtRest);
  if (in_motion) {
    const hw::TrajectoryPlan plan =
        trajectory_plan(spec, cfg.rate_hz, procedure_modes(spec, spec.sim.file), poses, end_s);
    auto robot = hw::make_hardware(cfg);
    description = fmt::format("{} backend from {}", cfg.backend, *spec.hardware);
    r.sampling_s = hw::run_trajectory_session(*robot, plan, log, signals.flag()).duration_s;
  } else {
    const hw::SessionPlan plan = session_plan(spec, poses, cfg.modes, cfg.dither_mm);
    auto robot = hw::make_hardware(cfg);
    description = fmt::format("{} backend from {}", cfg.backend, *spec.hardware);
    hw::run_sampling_session(*robot, plan, log, signals.flag());
  }
  // Every sample of the file (those resumed and those just taken), in id order.
  for (const auto& [id, row] : log.recorded()) r.samples.push_back(sample_record(id, row, r.actual));
  return r;
}

// The samples of log with the twin's truth of each (true angles, pose and
// speeds; at rest the drive torque and time of the averaging window).
std::vector<sim::SampleRecord> twin_samples(const hw::SampleLog& log, const TwinTruth& truth, const Robot& actual) {
  std::vector<sim::SampleRecord> out;
  for (const auto& [id, row] : log.recorded()) {
    sim::SampleRecord rec = sample_record(id, row, actual);
    if (const auto it = truth.samples().find(id); it != truth.samples().end()) {
      const SampleTruth& t = it->second;
      rec.theta_a = t.theta_a;
      rec.xy_mm = t.xy_mm;
      rec.omega = t.omega;
      if (!row.motion) rec.tau = rec.tau_last = rec.tau_between = t.tau, rec.t_s = t.t_s;
    }
    out.push_back(rec);
  }
  return out;
}

// The farthest the twin's end-effector went from the plan in rows (mm).
double worst_plan_deviation_mm(const std::vector<sim::LogRow>& rows) {
  double worst = 0.0;
  for (const sim::LogRow& row : rows) worst = std::max(worst, (row.actual - row.desired).norm());
  return worst;
}

// A session's stop line less its "; N samples kept in PATH" tail (the caller
// says where they are kept); a line without that tail as it is.
std::string without_kept_tail(const std::string& what, const std::string& kept_in) {
  const std::string tail = " samples kept in " + kept_in;
  if (!what.ends_with(tail)) return what;
  const std::size_t at = what.rfind("; ", what.size() - tail.size());
  return at == std::string::npos ? what : what.substr(0, at);
}

// A session on the twin stopped (its tracking watch, a refused command): the
// samples and the trajectory so far, kept as the twin's own stop keeps them.
sim::TrackingStop twin_stopped(const hw::HardwareError& e, const hw::SampleLog& log, const TwinTruth& truth,
                               sim::SimulationResult& r) {
  sim::TrackingStop stop(without_kept_tail(e.what(), log.path()));
  stop.samples = twin_samples(log, truth, r.actual);
  stop.rows = std::move(r.log.rows);
  stop.robot_time_s = truth.time_s();
  stop.ended_early = dynamic_cast<const hw::PathEndedEarly*>(&e) != nullptr;
  return stop;
}

// Samples on the in-process twin by the procedure of sample_on_hardware (the
// same sessions behind a safety supervisor) through the twin backend of the
// scenario's robot (run/twin_hardware.hpp): in process is --hardware with a
// twin backend by construction. The true poses, the trajectory log and
// model.xml come from the twin's truth.
sim::SimulationResult sample_on_twin(const RunSpec& spec, gpm::Progress* progress, double end_s = 0.0) {
  const sim::Scenario& s = spec.sim;
  sim::SimulationResult r;
  r.actual = sim::make_actual(s);
  if (s.twin.effects.thermal.on()) r.log.thermal_reference = r.actual.geometry;
  r.log.every = s.log_every;
  const std::vector<Eigen::Vector2d> poses = s.sampling ? sim::plan_poses(*s.sampling, s.seed)
                                                        : std::vector<Eigen::Vector2d>{};
  sim::check_targets(s, r.actual, poses);
  const bool in_motion = s.sampling && s.sampling->pattern == sim::PosePattern::kTrajectory;
  const std::array<hw::JointMode, 3> modes = twin_joint_modes(s);
  TwinHardware th = make_twin_hardware(s, r.actual, s.controller);
  TwinTruth truth(th, &r.log, progress);
  hw::SampleLog log(in_motion ? hw::SampleColumns::kOnTheFly : hw::SampleColumns::kAtRest);
  try {
    if (in_motion) {
      const hw::TrajectoryPlan plan = trajectory_plan(spec, s.twin.servo_rate_hz, modes, poses, end_s);
      r.sampling_s = hw::run_trajectory_session(*th.robot, plan, log, nullptr, truth.hook()).duration_s;
    } else if (!poses.empty()) {
      hw::SessionPlan plan = session_plan(spec, poses, modes, std::nullopt);
      plan.check_following = false;  // the twin's readings are its own; the check would change no sample
      r.sampling_s = hw::run_sampling_session(*th.robot, plan, log, nullptr, truth.hook()).duration_s;
    }
  } catch (const hw::HardwareError& e) {
    if (progress) progress->finish();
    throw twin_stopped(e, log, truth, r);
  }
  if (progress) progress->finish();
  r.samples = twin_samples(log, truth, r.actual);
  r.model_xml = th.twin->model(modes).xml();
  r.simulated_s = truth.time_s();
  r.max_violation_m = r.log.max_violation_m;
  r.max_torque = r.log.max_torque;
  return r;
}

// What a run will command and estimate, checked before anything moves: the
// accuracy test's targets and the reference pose (named by scenario key), and
// a free set that the LM stage would refuse as unidentifiable (the similarity
// gauge), from noiseless readings on two circles round home.
void check_before_moving(const RunSpec& spec) {
  const bool targets = spec.compensation || spec.calibration.reference_at;
  const Robot actual = targets ? sim::make_actual(spec.sim) : Robot{};
  if (spec.compensation) {
    sim::check_poses_reach(spec.sim, actual, spec.compensation->poses, "compensation.poses");
    sim::check_path_reach(spec.sim, actual, spec.compensation->path, "compensation.path");
  }
  if (spec.calibration.reference_at)
    sim::check_poses_reach(spec.sim, actual, {*spec.calibration.reference_at}, "calibration.reference_at");
  const bool lm_refuses_rank = spec.calibration.method == calib::Method::kLM ||
                               (spec.calibration.method == calib::Method::kDELM && spec.calibration.cost == calib::Cost::kML);
  if (!lm_refuses_rank || spec.calibration.allow_rank_deficient || spec.expect.refused_contains) return;
  const Robot& c = spec.sim.controller;
  const FreeMask free = ~spec.calibration.fixed;
  std::vector<Eigen::Vector3d> theta;
  for (double radius : {40.0, 80.0})
    for (const Eigen::Vector2d& p : circle_points(c.home, radius, 12))
      if (const Reach r = check_reach(c, p); r.ok) theta.push_back(readings_from_active(c.geometry, r.q.theta_a));
  if (theta.size() >= free.count()) calib::require_identifiable(calib::analyse_identifiability(theta, c.geometry, free), free);
}

// The calibration's options from spec: start (with the reference-point
// procedure, the readings where the actual robot stands), free set, reading
// sigma, solver; on the fly or not is the caller's.
ProcedureOptions procedure_options(const RunSpec& spec, const Robot& nominal, const Robot& actual) {
  ProcedureOptions po;
  po.start = spec.sim.controller.geometry;
  po.free = ~spec.calibration.fixed;
  // The fixed coordinates define the frame: they must be the true ones (docs/PAPER_NOTES.md).
  if (spec.calibration.start_reference) {
    // Paper section 3.2 step 3: readings where the robot stands, taken as if at home.
    const JointAngles q = inverse_kinematics(actual.geometry, spec.calibration.reference_at.value_or(actual.home),
                                             actual.branch);
    const Eigen::Vector3d m = readings_from_active(actual.geometry, q.theta_a);
    const JointAngles qn = inverse_kinematics(po.start, nominal.home, nominal.branch);
    for (int i = 0; i < 3; ++i) po.start[dth(i)] = wrap_pi(qn.theta_a[i] - m[i]);
  }
  po.sigma_rad = spec.calibration.sigma.value_or(effective_sigma(spec.sim));
  po.sigma_from_step = !spec.calibration.sigma.has_value();
  po.reading_noise_rad = spec.sim.twin.encoder.noise_rad;
  po.keep_clearance = spec.calibration.estimate_clearance.has_value();
  calib::MethodOptions& mo = po.method;
  mo.method = spec.calibration.method;
  mo.cost = spec.calibration.cost;
  mo.budget = spec.calibration.budget;
  if (spec.calibration.lm_iterations) mo.lm_max_iterations = *spec.calibration.lm_iterations;
  mo.seed = spec.calibration.seed;
  mo.encoder_sigma = spec.calibration.sigma;
  if (!mo.encoder_sigma && spec.sim.twin.encoder.noise_rad > 0) mo.encoder_sigma = po.sigma_rad;
  mo.allow_rank_deficient = spec.calibration.allow_rank_deficient;
  mo.loss = spec.calibration.loss;
  po.home = calib::HomePose{nominal.home, nominal.branch};
  return po;
}

// What the drives reported of each sample: readings, times, and the torque
// the twist follows (torque_history: the twin's record of the torques before
// each reading on the fly, tau_last and tau_between; else the sample's).
SampleSeries sample_series(const std::vector<sim::SampleRecord>& samples, bool torque_history) {
  SampleSeries s;
  for (const sim::SampleRecord& r : samples) {
    s.theta_m.push_back(r.theta_m);
    s.t_s.push_back(r.t_s);
    s.tau.push_back(torque_history ? r.tau_last : r.tau);
    if (torque_history) s.tau_between.push_back(r.tau_between);
    s.read_lag_s.push_back(r.read_lag_s);
  }
  return s;
}

// The motion model's estimates into o, and the Cramer-Rao bound at the truth
// of the joint estimation (with the clearance or the cyclic error carried: the
// samples the procedure keeps, the cyclic error's prior, at the reading noise
// itself) or of the samples the fit used.
void take_motion_fit(RunOutcome& o, const CalibrationOutcome& c, const FreeMask& free, const Geometry& truth,
                     const std::vector<Eigen::Vector3d>& noiseless) {
  o.motion_nu = c.fit.nu;
  o.motion_nu_sigma = c.fit.nu_sigma;
  o.reading_estimated = c.reading;
  o.friction_balance = c.friction_balance;
  const double sigma = o.crb_sigma_rad;
  if ((c.motion.clearance || c.motion.cyclic_prior_rad > 0.0) && sigma > 0.0) {
    o.crb = scaled_bound(
        [&] {
          std::array<double, kNumParams> b =
              calib::motion_crb(truth, free, noiseless, c.omega, c.tau, c.motion, c.alpha, sigma);
          for (double& v : b) v /= sigma;
          return b;
        },
        sigma);
  } else if (c.fit.kept.size() < noiseless.size()) {
    std::vector<Eigen::Vector3d> kept_noiseless;
    for (std::size_t j : c.fit.kept) kept_noiseless.push_back(noiseless[j]);
    o.crb = scaled_bound([&] { return calib::crb_sigma(truth, free, kept_noiseless, 1.0); }, sigma);
  }
}

// RunOutcome::positioning_bound_um of o's calibration c in motion (none
// when the information is singular or no point of the disc is reachable).
std::optional<double> positioning_bound(const RunOutcome& o, const CalibrationOutcome& c, const FreeMask& free,
                                        const std::vector<Eigen::Vector3d>& noiseless) {
  calib::MotionModel estimated = c.motion;
  estimated.estimate_cyclic = estimated.cyclic_prior_rad > 0.0;  // the carried error's columns in the bound
  try {
    const Eigen::Matrix<double, kNumParams, kNumParams> C = calib::motion_crb_covariance(
        o.sim.actual.geometry, free, noiseless, c.omega, c.tau, estimated, c.alpha, o.crb_sigma_rad);
    if (!C.allFinite()) return std::nullopt;
    const calib::PositioningError e =
        calib::positioning_error(o.sim.actual, o.sim.actual, calib::WorkspaceDisc{o.nominal.home}, C);
    return std::sqrt(2.0) * e.stated_sigma_rms_um;  // the 1-sigma per axis to the RMS of |e|
  } catch (const InputError&) {
    return std::nullopt;
  }
}

using Stage = std::function<void(const std::string&)>;

// The run-time pose design of spec's sampling; with hardware the poses must
// pass its safety limits too.
void design_poses(RunSpec& spec, const Stage& stage) {
  stage("designing the calibration poses");
  std::function<bool(const Eigen::Vector2d&)> admissible;
  std::optional<hw::HardwareConfig> hw_cfg;
  if (spec.hardware) {  // the poses must pass the hardware's safety limits too
    hw_cfg = hw::load_hardware_config(*spec.hardware);
    // With room to brake: 5 mm inside the workspace disc, 0.02 rad inside the joint limits.
    hw_cfg->safety.workspace_margin_mm += 5.0;
    for (int i = 0; i < 3; ++i) hw_cfg->safety.joint_min[i] += 0.02, hw_cfg->safety.joint_max[i] -= 0.02;
    admissible = [&hw_cfg](const Eigen::Vector2d& p) {
      return hw::target_violation(hw_cfg->safety, hw_cfg->controller, p, hw_cfg->modes).empty();
    };
  }
  design_sampling(spec.sim, ~spec.calibration.fixed, effective_sigma(spec.sim), admissible);
}

// The calibration of out's samples (run/calibration_procedure.hpp) with
// inputs, from the encoder samples alone; the Cramer-Rao bound at the truth
// and the residuals. Samples it cannot use fail the run (gpm::Error) unless
// the scenario expects the refusal.
void calibrate_run(RunOutcome& out, const RunSpec& spec, const CalibrationInputs& inputs, const std::string& scenario_file,
                   const Stage& stage) {
  const Robot& actual = out.sim.actual;
  const bool in_motion = out.in_motion;
  std::vector<Eigen::Vector2d> true_xy;
  std::vector<Eigen::Vector3d> noiseless;
  for (const sim::SampleRecord& r : out.sim.samples) {
    true_xy.push_back(r.xy_mm);
    noiseless.push_back(readings_from_active(actual.geometry, r.theta_a));
  }
  ProcedureOptions po = procedure_options(spec, out.nominal, actual);
  po.in_motion = in_motion;
  out.crb_sigma_rad = po.sigma_rad;
  if (po.free.count() <= noiseless.size()) {
    out.crb = scaled_bound([&] { return calib::crb_sigma(actual.geometry, po.free, noiseless, 1.0); },
                           out.crb_sigma_rad);
  } else {
    out.crb.fill(NAN);
  }

  stage("calibrating");
  std::vector<Eigen::Vector3d> used;  // the readings the fit explains
  try {
    // Transmission compliance, latch skew, friction twist and clearance are
    // estimated jointly with the geometry where inputs.motion says so
    // (run/calibration_procedure.hpp); on the fly (the twin records the
    // drives' torque history) the twist follows the torques the drives applied
    // before each reading (the twin and the drives record them alike);
    // samples stop-and-go use the drive torque of the sample.
    const bool torque_history = in_motion;
    SampleSeries series = sample_series(out.sim.samples, torque_history);
    if (!spec.hardware) series.true_xy = true_xy;  // the true poses in simulation (kmrmse only then)
    CalibrationOutcome c = calibrate_samples(series, inputs, po);
    if (c.sigma_rad != out.crb_sigma_rad && out.crb_sigma_rad > 0.0) {
      // The readings' own step: the bound scales with the reading 1-sigma.
      for (double& v : out.crb) v *= c.sigma_rad / out.crb_sigma_rad;
      out.crb_sigma_rad = c.sigma_rad;
    }
    out.calibration = c.result;
    used = c.used;
    out.model_test = c.model_test;
    if (c.with_effects) take_motion_fit(out, c, po.free, actual.geometry, noiseless);
    if (c.with_effects && !spec.hardware && out.crb_sigma_rad > 0.0)
      out.positioning_bound_um = positioning_bound(out, c, po.free, noiseless);
    // A result that is not a robot (a link of no length, home out of reach)
    // fails the run (gpm::Error, exit 1) instead of becoming the controller.
    out.calibrated = calib::usable_robot(out.calibrated, out.calibration->geometry);
  } catch (const InputError& e) {
    // The scenario was valid and the robot ran: samples that cannot be
    // calibrated are the run's outcome (exit 1), not bad input.
    if (!spec.expect.refused_contains)
      throw Error(fmt::format("{}: the calibration cannot use this run's samples: {}", scenario_file, e.what()));
    out.refused = e.what();
  }

  if (out.calibration) {
    for (const Eigen::Vector3d& m : used) {
      double r = NAN;
      const calib::MlResidual residual(m);
      residual(out.calibration->geometry.values.data(), &r);
      out.residual_urad.push_back(r * 1e6);
    }
  }

}

// The accuracy test of spec.compensation on the twin: the nominal, the
// calibrated and (simulation only) the actual parameters.
void measure_compensation(RunOutcome& out, const RunSpec& spec, const Progress& progress, const Stage& stage) {
  const Robot& actual = out.sim.actual;
  // A torque-mode joint preloads the chain for the sampling only; the
  // accuracy test runs the robot as in operation (that joint torque-off).
  sim::TwinConfig test_twin = spec.sim.twin;
  for (sim::ServoDrive& d : test_twin.drives)
    if (d.mode == sim::ServoMode::kTorque) d.mode = sim::ServoMode::kTorqueOff;
  stage("measuring accuracy with the nominal model");
  const unsigned long long seed = derive_seed(spec.sim.seed, Stream::kAccuracyTest);
  // A progress line per measurement on a terminal (models/progress.hpp): test poses, then the path.
  std::optional<gpm::Progress> measuring;
  const auto steps = [&](const std::string& label) -> gpm::Progress& {
    measuring.reset();
    measuring.emplace(progress ? gpm::Progress::terminal("gpm run: " + label, "test steps",
                                                         static_cast<double>(spec.compensation->poses.size() + 1))
                               : gpm::Progress::silent());
    return *measuring;
  };
  out.before = measure_accuracy(actual, test_twin, out.nominal, *spec.compensation, seed, "nominal",
                               &steps("nominal model"), spec.sim.max_tracking_mm);
  if (out.calibration) {
    stage("measuring accuracy with the calibrated model");
    // The controller compensates the drive-train harmonics the calibration estimated (none: its geometry alone).
    const bool harmonics = out.reading_estimated && std::ranges::any_of(out.reading_estimated->harmonic, [](const auto& h) {
                             return std::ranges::any_of(h, [](double v) { return v != 0.0; });
                           });
    out.after = measure_accuracy(actual, test_twin, out.calibrated, *spec.compensation, seed, "calibrated",
                                 &steps("calibrated model"), spec.sim.max_tracking_mm, false,
                                 harmonics ? &*out.reading_estimated : nullptr);
  }
  if (!spec.hardware) {
    stage("measuring accuracy with the actual parameters and reading errors (the floor)");
    Robot truth = out.nominal;
    truth.geometry = actual.geometry;
    out.floor = measure_accuracy(actual, test_twin, truth, *spec.compensation, seed, "actual",
                                 &steps("actual parameters"), spec.sim.max_tracking_mm, true);
    if (out.after)
      out.floor_ratio_ci95 = rms_ratio_interval(out.after->static_error_um, out.floor->static_error_um,
                                                derive_seed(spec.sim.seed, Stream::kAccuracyTest) + 1);
  }
}

// The offsets stage's length where the path is sampled on the fly
// (sampling.offsets_first_s); 0 otherwise or when none is stated.
double offsets_stage_s(const RunSpec& spec) {
  const auto& p = spec.sim.sampling;
  return p && p->pattern == sim::PosePattern::kTrajectory ? p->offsets_first_s : 0.0;
}

std::string offsets_stage_why(double stage_s) {
  return fmt::format("the offsets stage: the path's first {:g} s, then retraced to its start", stage_s);
}

// After a first pass of the path on the fly (the offsets stage, planned, or a
// pass that ended early): the encoder offsets its kept samples show
// (run/offsets_first.hpp offsets_learnt, the rest of the geometry as
// uncertain as the path's margin states it) become the controller's and the robot stays the
// one it was (the twin's actual parameters are drawn about the controller's:
// held). The poses stay: their design does not depend on the offsets, which
// only relabel the readings (SamplingDesign.ADesignIsRememberedForItsInputsOnly).
FirstPass plan_second_pass(RunSpec& spec, const std::vector<sim::SampleRecord>& kept, const std::string& why,
                           double robot_time_s, bool planned, const Stage& stage) {
  stage(planned ? "fitting the encoder offsets to the offsets stage's samples"
                : "the path ended early: fitting the encoder offsets to the samples kept, planning it again");
  const OffsetsEstimate fit = offsets_learnt(spec.sim.controller.geometry, kept, spec.sim.sampling->margin.tolerance);
  FirstPass first;
  first.why = why;
  first.planned = planned;
  first.samples = kept.size();
  first.robot_time_s = robot_time_s;
  for (int i = 0; i < 3; ++i) {
    first.offsets_change_rad[i] = fit.geometry.dth_(i) - spec.sim.controller.geometry.dth_(i);
    first.offsets_sigma_rad[i] = fit.sigma_rad[static_cast<std::size_t>(i)];
  }
  const Robot actual = sim::make_actual(spec.sim);
  for (int k = 0; k < kNumParams; ++k) spec.sim.actual.explicit_values[static_cast<std::size_t>(k)] = actual.geometry[k];
  spec.sim.controller.geometry = fit.geometry;
  return first;
}

// Samples on the twin (sample_on_twin) in passes: with an offsets stage
// (offsets_stage_s) its samples, and otherwise a path on the fly that ended
// early (sim::TrackingStop::ended_early) with at least kMinFirstPassSamples
// kept, plan the second pass (plan_second_pass), whose samples are the
// calibration's; the robot time is both passes'. The second pass ending
// early too stops as the first.
sim::SimulationResult sample_twin_in_passes(RunOutcome& out, RunSpec& spec, const Progress& progress,
                                            const Stage& stage) {
  const auto simulating = [&] {
    return progress ? gpm::Progress::terminal("gpm run: simulating", "simulated s") : gpm::Progress::silent();
  };
  const double stage_s = offsets_stage_s(spec);
  try {
    gpm::Progress simulated = simulating();
    sim::SimulationResult r = sample_on_twin(spec, &simulated, stage_s);
    out.plan_deviation_mm = worst_plan_deviation_mm(r.log.rows);
    if (stage_s <= 0.0) return r;
    out.first_pass = plan_second_pass(spec, r.samples, offsets_stage_why(stage_s), r.sampling_s, true, stage);
  } catch (const sim::TrackingStop& stop) {
    if (!stop.ended_early || static_cast<int>(stop.samples.size()) < kMinFirstPassSamples) throw;  // on the fly only
    out.first_pass = plan_second_pass(spec, stop.samples, stop.what(), stop.robot_time_s, false, stage);
    out.plan_deviation_mm = worst_plan_deviation_mm(stop.rows);
  }
  stage("sampling on the twin through the hardware interface, second pass");
  gpm::Progress simulated = simulating();
  sim::SimulationResult r = sample_on_twin(spec, &simulated);
  r.sampling_s += out.first_pass->robot_time_s;
  out.plan_deviation_mm = std::max(out.plan_deviation_mm, worst_plan_deviation_mm(r.log.rows));
  return r;
}

// The samples of a hardware session's file, read back (the file stays).
std::vector<sim::SampleRecord> recorded_samples(const std::string& path, const RunSpec& spec) {
  const hw::SampleLog log(path, true, hw::SampleColumns::kOnTheFly);
  const Robot actual = sim::make_actual(spec.sim);
  std::vector<sim::SampleRecord> out;
  for (const auto& [id, row] : log.recorded()) out.push_back(sample_record(id, row, actual));
  return out;
}

// The first pass through the hardware interface: the offsets stage (stage_s
// > 0) into first_path, or the whole path into samples_path, whose file
// becomes first_path when it ends early (nullopt: it did not, r holds the
// calibration's samples).
std::optional<FirstPass> first_pass_on_hardware(RunSpec& spec, const std::string& samples_path,
                                                const std::string& first_path, double stage_s,
                                                std::string& description, sim::SimulationResult& r,
                                                const Stage& stage) {
  const std::string& path = stage_s > 0.0 ? first_path : samples_path;
  try {
    r = sample_on_hardware(spec, path, description, Eigen::Vector3d::Zero(), stage_s);
    if (stage_s <= 0.0) return std::nullopt;
    return plan_second_pass(spec, r.samples, offsets_stage_why(stage_s), r.sampling_s, true, stage);
  } catch (const hw::PathEndedEarly& e) {  // only a path on the fly ends early
    std::vector<sim::SampleRecord> kept = recorded_samples(path, spec);
    if (static_cast<int>(kept.size()) < kMinFirstPassSamples) throw;
    if (path != first_path) std::filesystem::rename(path, first_path);
    return plan_second_pass(spec, kept, without_kept_tail(e.what(), path), e.duration_s, false, stage);
  }
}

// Samples through the hardware interface (sample_on_hardware) in passes as
// sample_twin_in_passes: the first pass's samples (the offsets stage's, or a
// path that ended early) are kept in first_pass_samples_path(samples_path)
// and the second pass records into samples_path. A resumed session whose
// folder holds that file plans the second pass from it (its robot time is
// then not known: 0).
sim::SimulationResult sample_hardware_in_passes(RunOutcome& out, RunSpec& spec, const std::string& samples_path,
                                                const Stage& stage) {
  const bool in_motion = spec.sim.sampling && spec.sim.sampling->pattern == sim::PosePattern::kTrajectory;
  const std::string first_path = first_pass_samples_path(samples_path);
  if (in_motion && spec.hardware_resume && std::filesystem::exists(first_path)) {
    out.first_pass = plan_second_pass(spec, recorded_samples(first_path, spec), "in an earlier session of this folder",
                                      0.0, offsets_stage_s(spec) > 0.0, stage);
  } else {
    sim::SimulationResult r;
    out.first_pass = first_pass_on_hardware(spec, samples_path, first_path, in_motion ? offsets_stage_s(spec) : 0.0,
                                            out.hardware_description, r, stage);
    if (!out.first_pass) return r;
  }
  stage("sampling through the hardware interface, second pass");
  const Eigen::Vector3d dth_change(out.first_pass->offsets_change_rad.data());
  sim::SimulationResult r = sample_on_hardware(spec, samples_path, out.hardware_description, dth_change);
  r.sampling_s += out.first_pass->robot_time_s;
  return r;
}

}  // namespace

sim::SimulationResult sample_in_process(const RunSpec& spec) { return sample_on_twin(spec, nullptr); }

RunOutcome run_scenario(const RunSpec& spec_in, const std::string& scenario_file, const Progress& progress,
                        const std::string& samples_path) {
  const auto t0 = std::chrono::steady_clock::now();
  auto stage = [&](const std::string& s) { if (progress) progress(s); };
  RunSpec spec = spec_in;
  // events: belong to the operation (the monitor's twin time); the
  // calibration's sampling and accuracy tests run on the mechanism before them.
  const std::vector<sim::GeometryEvent> operation_events = std::move(spec.sim.twin.events);
  spec.sim.twin.events.clear();
  check_before_moving(spec);
  if (spec.sim.sampling && !spec.sim.sampling->needs_design())
    design_sampling(spec.sim, ~spec.calibration.fixed, 0.0);  // given poses: only their number is checked
  const bool designed = spec.sim.sampling && spec.sim.sampling->needs_design();
  if (designed) design_poses(spec, stage);
  const bool in_motion = spec.sim.sampling && spec.sim.sampling->pattern == sim::PosePattern::kTrajectory;
  // What the calibration assumes is what its user states (calibration:) and
  // the robot's data sheet, as on a real robot: the twin's effects and
  // design values (the simulated truth) are not read (run/calibration_inputs.hpp).
  const CalibrationInputs inputs = calibration_inputs(spec, spec.sim.controller);
  const calib::MotionModel& motion = inputs.motion;
  const bool with_effects = motion.compliance || motion.skew || motion.clearance;
  if (with_effects && (spec.calibration.method != calib::Method::kLM || spec.calibration.cost != calib::Cost::kML))
    throw InputError(fmt::format("{}: estimating compliance, skew or clearance with the geometry (samples on the fly, or "
                                 "calibration.estimate) needs calibration {{method: lm, cost: ml}}", scenario_file));
  if (with_effects && spec.hardware && !in_motion)
    throw InputError(fmt::format("{}: calibration.estimate needs the drive torques and speeds of each sample, which "
                                 "the hardware interface records on the fly only (sampling.pattern: trajectory)",
                                 scenario_file));
  RunOutcome out;
  out.scenario_file = scenario_file;
  out.spec = spec;
  out.spec.sim.twin.events = operation_events;  // for the monitor of the operation
  out.in_motion = in_motion;
  out.nominal = spec.sim.controller;
  out.calibrated = spec.sim.controller;

  if (spec.hardware) {
    stage("sampling through the hardware interface");
    out.sim = sample_hardware_in_passes(out, spec, samples_path, stage);
  } else {
    stage("sampling on the twin through the hardware interface");
    out.sim = sample_twin_in_passes(out, spec, progress, stage);
  }
  calibrate_run(out, spec, inputs, scenario_file, stage);
  if (out.first_pass && out.calibration)
    out.calibration->notes.push_back(fmt::format(
        "the first pass of the excitation path {} ({}); the encoder offsets from its {} samples planned "
        "the second pass, whose samples these are",
        out.first_pass->planned ? "ended as planned" : "ended early", out.first_pass->why, out.first_pass->samples));

  if (spec.compensation) measure_compensation(out, spec, progress, stage);
  if (out.calibration && !spec.hardware) out.positioning = calibrated_positioning(out);
  if (out.calibration && spec.hardware) out.stated_positioning = calib::stated_positioning(out.nominal, *out.calibration);
  if (spec.sim.operation) {
    stage("monitoring the operation with the calibrated model");
    out.monitor = monitor_after_calibration(out);
  }
  out.checks = evaluate_expectations(out);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

HardwareSampling sample_through_hardware(const RunSpec& spec_in, const std::string& samples_path,
                                         const Progress& progress) {
  const auto stage = [&](const std::string& s) { if (progress) progress(s); };
  if (!spec_in.hardware) throw InputError(spec_in.sim.file + ": sampling through hardware needs a hardware file");
  if (!spec_in.sim.sampling) throw InputError(spec_in.sim.file + ": the scenario has no 'sampling' section (poses to sample)");
  RunSpec spec = spec_in;
  spec.sim.twin.events.clear();  // events belong to the operation, not to the sampling
  check_before_moving(spec);
  const bool designed = spec.sim.sampling->needs_design();
  if (designed) design_poses(spec, stage);
  else design_sampling(spec.sim, ~spec.calibration.fixed, 0.0);  // given poses: only their number is checked
  RunOutcome out;
  stage("sampling through the hardware interface");
  const sim::SimulationResult r = sample_hardware_in_passes(out, spec, samples_path, stage);
  return HardwareSampling{out.hardware_description, r.samples.size(), r.sampling_s, out.first_pass};
}

std::string first_pass_samples_path(const std::string& samples_path) {
  const std::filesystem::path p(samples_path);
  return (p.parent_path() / (p.stem().string() + "_first_pass" + p.extension().string())).string();
}

const std::vector<std::string>& run_output_names() {
  static const std::vector<std::string> names{
      "samples.csv", "samples_first_pass.csv", "trajectory.csv", "model.xml", "actual.yaml", "calibration.yaml", "summary.json",
      "alarms.csv", "estimates.csv", "report.md", "report.html", "layout.svg", "residuals.svg",
      "convergence.svg", "errors_mm.svg", "errors_offsets.svg", "tracking.svg", "monitor_tracks.svg"};
  return names;
}

void write_run(const RunOutcome& o, const std::string& dir, const MeasuredFolder* measured) {
  // All or nothing (models/output_file.hpp); other files of the folder are kept.
  OutputFolder out(dir, {o.scenario_file}, measured);
  if (o.hardware_description.empty()) {  // with hardware the session already wrote samples.csv
    out.add("samples.csv", sim::samples_csv(o.sim.samples));
    out.add("trajectory.csv", sim::trajectory_csv(o.sim.log));
    out.add("model.xml", o.sim.model_xml);
  }
  out.add("actual.yaml", robot_to_yaml(o.sim.actual));
  // The result, and the reading model the monitor of this robot assumes (the
  // calibration's estimates where it made them, the statement for the rest).
  if (o.calibration)
    out.add("calibration.yaml", calib::result_to_yaml(*o.calibration, o.nominal.name) +
                                    monitor_reading_model_yaml(reading_model_after_calibration(o)));
  out.add("summary.json", summary_json(o));
  if (o.positioning) out.add("positioning.csv", calib::positioning_csv(*o.positioning));
  if (o.monitor) {
    out.add("alarms.csv", monitor_alarms_csv(*o.monitor));
    out.add("estimates.csv", monitor_estimates_csv(*o.monitor));
  }
  if (o.spec.outputs.report) {
    report::ReportDocument doc = report::build_run_report(run_report_data(o));
    if (o.monitor) {
      doc.heading(2, "Monitoring the operation with the calibrated model");
      add_monitor_section(doc, *o.monitor, 3, "monitor_tracks");
    }
    doc.stage(out, "report", fmt::format("gpm run: {}", o.spec.sim.name));
  }
  out.commit();
}

}  // namespace gpm::scenario
