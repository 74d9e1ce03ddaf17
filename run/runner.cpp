#include "run/runner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "calib/identifiability.hpp"
#include "calib/calibrate.hpp"
#include "calib/crb.hpp"
#include "calib/friction_profile.hpp"
#include "calib/model_test.hpp"
#include "calib/reading_model_selection.hpp"
#include "calib/reading_step.hpp"
#include "calib/motion_correction.hpp"
#include "calib/reading_rates.hpp"
#include "calib/residuals.hpp"
#include "calib/result_yaml.hpp"
#include "models/pose_layouts.hpp"
#include "models/errors.hpp"
#include "models/kinematics.hpp"
#include "models/output_file.hpp"
#include "hw/hardware_config.hpp"
#include "hw/safety_limits.hpp"
#include "hw/procedures/sample_log.hpp"
#include "hw/procedures/sampling_session.hpp"
#include "hw/procedures/stop_on_signal.hpp"
#include "models/robot_yaml.hpp"
#include "models/samples.hpp"
#include "run/calibration_inputs.hpp"
#include "run/expectations.hpp"
#include "run/run_report_data.hpp"
#include "run/sampling_design.hpp"
#include "run/summary_json.hpp"

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
                                    o.calibration->covariance);
  } catch (const InputError&) {
    return std::nullopt;
  }
}

// Samples on the fly left out at the start with a compliant transmission (s).
constexpr double kStartTransient_s = 0.05;

// On the fly, the joint accelerations are differences of the reading
// speeds over +-this (s; calib/reading_rates.hpp: the speeds are central
// differences over +-1 sample). Noise of 17-bit readings (q = 4.8e-5 rad)
// at a 1 ms sample interval h: q / (sqrt 12 2 h w) = 0.86 rad/s^2 at w = 8 ms,
// against q / (4 sqrt 2 h^2) = 8.5 rad/s^2 at w = h, which made the main job's chi2/dof 1.44
// (8 ms: 1.08; 4 and 12 ms alike; 16 ms failed its 3 CRB sigmas, 4.7).
constexpr double kAccelerationHalfWindow_s = 8e-3;

// "value: chi2/dof" of each value a model-test profile tried (the run's
// notes), the values formatted with value_format.
std::string profile_tried(const calib::FrictionProfile& p, std::string_view value_format) {
  std::string out;
  for (std::size_t k = 0; k < p.scales.size(); ++k)
    out += fmt::format("{}{}: {:.3g}", k ? ", " : "", fmt::format(fmt::runtime(value_format), p.scales[k]), p.chi2_per_dof[k]);
  return out;
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

// Samples through the hardware interface (hw/): the scenario's poses, the
// sampling session of hw/procedures/sampling_session.hpp, every sample on disk as taken.
sim::SimulationResult sample_on_hardware(const RunSpec& spec, const std::string& samples_path,
                                         std::string& description) {
  if (samples_path.empty()) throw InputError("gpm run --hardware: no output folder for the samples");
  const hw::HardwareConfig cfg = hw::load_hardware_config(*spec.hardware);
  hw::SessionPlan plan;
  plan.poses = sim::plan_poses(*spec.sim.sampling, spec.sim.seed);
  plan.options = spec.sim.sampling->options;
  plan.modes = cfg.modes;
  if (cfg.dither_mm) plan.dither_mm = *cfg.dither_mm;
  sim::SimulationResult r;
  r.actual = sim::make_actual(spec.sim);
  const hw::StopOnSignal signals;  // hw/procedures/stop_on_signal.hpp: drives off, exit 130
  hw::SampleLog log(samples_path, spec.hardware_resume);
  {
    auto robot = hw::make_hardware(cfg);
    description = fmt::format("{} backend from {}", cfg.backend, *spec.hardware);
    hw::run_sampling_session(*robot, plan, log, signals.flag());
  }
  // Every sample of the file (those resumed and those just taken), in id order.
  for (const auto& [id, row] : log.recorded()) {
    sim::SampleRecord rec;
    rec.id = id;
    rec.theta_m = row.theta_m;
    rec.target = plan.poses[static_cast<size_t>(id)];
    // Through the interface only the readings are known; the pose is the
    // target, and the true angles those of the scenario's actual robot there.
    rec.xy_mm = rec.target;
    rec.theta_a = inverse_kinematics(r.actual.geometry, rec.target, r.actual.branch).theta_a;
    rec.settled = true;
    r.samples.push_back(rec);
  }
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

}  // namespace

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
  if (spec.sim.sampling && spec.sim.sampling->needs_design()) {
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
  const bool in_motion = spec.sim.sampling && spec.sim.sampling->pattern == sim::PosePattern::kTrajectory;
  if (in_motion && spec.hardware)
    throw InputError(fmt::format("{}: sampling.pattern: trajectory runs on the twin only (the hardware interface "
                                 "samples stop-and-go); use pattern: designed with --hardware", scenario_file));
  // What the calibration assumes is what its user states (calibration:) and
  // the robot's data sheet, as on a real robot: the twin's effects and
  // design values (the simulated truth) are not read (run/calibration_inputs.hpp).
  const CalibrationInputs inputs = calibration_inputs(spec, spec.sim.controller);
  calib::MotionModel motion = inputs.motion;
  const bool with_effects = motion.compliance || motion.skew || motion.clearance;
  if (with_effects && (spec.calibration.method != calib::Method::kLM || spec.calibration.cost != calib::Cost::kML))
    throw InputError(fmt::format("{}: estimating compliance, skew or clearance with the geometry (samples on the fly, or "
                                 "calibration.estimate) needs calibration {{method: lm, cost: ml}}", scenario_file));
  if (with_effects && spec.hardware)
    throw InputError(fmt::format("{}: calibration.estimate needs the drive torques and speeds of each sample, which "
                                 "the hardware interface does not record yet", scenario_file));
  RunOutcome out;
  out.scenario_file = scenario_file;
  out.spec = spec;
  out.spec.sim.twin.events = operation_events;  // for the monitor of the operation
  out.in_motion = in_motion;
  out.nominal = spec.sim.controller;
  out.calibrated = spec.sim.controller;

  if (spec.hardware) {
    stage("sampling through the hardware interface");
    out.sim = sample_on_hardware(spec, samples_path, out.hardware_description);
  } else {
    stage("simulating the twin");
    gpm::Progress simulated = progress ? gpm::Progress::terminal("gpm run: simulating", "simulated s")
                                       : gpm::Progress::silent();  // models/progress.hpp
    out.sim = sim::run_simulation(spec.sim, nullptr, &simulated);
  }
  const Robot& actual = out.sim.actual;

  // Calibration problem from the encoder samples alone.
  calib::Problem problem;
  std::vector<Eigen::Vector2d> true_xy;
  std::vector<Eigen::Vector3d> noiseless;
  for (const sim::SampleRecord& r : out.sim.samples) {
    problem.theta_m.push_back(r.theta_m);
    true_xy.push_back(r.xy_mm);  // the true pose in simulation (kmrmse only then)
    noiseless.push_back(readings_from_active(actual.geometry, r.theta_a));
  }
  problem.start = spec.sim.controller.geometry;
  problem.free = ~spec.calibration.fixed;
  // The fixed coordinates define the frame: they must be the true ones (docs/PAPER_NOTES.md).
  if (spec.calibration.start_reference) {
    // Paper section 3.2 step 3: readings where the robot stands, taken as if at home.
    const JointAngles q = inverse_kinematics(actual.geometry, spec.calibration.reference_at.value_or(actual.home),
                                             actual.branch);
    const Eigen::Vector3d m = readings_from_active(actual.geometry, q.theta_a);
    const JointAngles qn = inverse_kinematics(problem.start, out.nominal.home, out.nominal.branch);
    for (int i = 0; i < 3; ++i) problem.start[dth(i)] = wrap_pi(qn.theta_a[i] - m[i]);
  }

  out.crb_sigma_rad = spec.calibration.sigma.value_or(effective_sigma(spec.sim));
  std::string step_note;
  if (in_motion && !spec.calibration.sigma) {
    // Single readings on the fly show their encoders' step (calib/reading_step.hpp):
    // a geared drive's motor encoder is finer at the joint than its bits say.
    if (const std::optional<double> q = calib::reading_step(problem.theta_m)) {
      const double noise = spec.sim.twin.encoder.noise_rad;
      out.crb_sigma_rad = std::sqrt(*q * *q / 12.0 + noise * noise);
      step_note = fmt::format("reading resolution from the samples: {:.4g} rad ({:.4g} counts per joint revolution), "
                              "reading 1-sigma {:.3g} rad",
                              *q, 2.0 * M_PI / *q, out.crb_sigma_rad);
    }
  }
  if (problem.free.count() <= noiseless.size()) {
    out.crb = scaled_bound([&] { return calib::crb_sigma(actual.geometry, problem.free, noiseless, 1.0); },
                           out.crb_sigma_rad);
  } else {
    out.crb.fill(NAN);
  }

  stage("calibrating");
  calib::MethodOptions mo;
  mo.method = spec.calibration.method;
  mo.cost = spec.calibration.cost;
  mo.budget = spec.calibration.budget;
  if (spec.calibration.lm_iterations) mo.lm_max_iterations = *spec.calibration.lm_iterations;
  mo.seed = spec.calibration.seed;
  mo.encoder_sigma = spec.calibration.sigma;
  if (!mo.encoder_sigma && spec.sim.twin.encoder.noise_rad > 0) mo.encoder_sigma = out.crb_sigma_rad;
  mo.allow_rank_deficient = spec.calibration.allow_rank_deficient;
  mo.loss = spec.calibration.loss;
  mo.true_xy = spec.hardware ? nullptr : &true_xy;
  std::vector<Eigen::Vector3d> used = problem.theta_m;  // the readings the fit explains
  try {
    if (with_effects) {
      // Transmission compliance (readings follow the motors, links lag by
      // compliance x torque) and latch skew are estimated jointly with the
      // geometry (calib/motion_correction.hpp).
      // The joints' speeds and accelerations: on the fly from the readings
      // themselves (calib/reading_rates.hpp: centred differences over the
      // consecutive samples, sample_every drive periods apart: speeds central
      // over +-1 sample, accelerations over +-kAccelerationHalfWindow_s; a real robot
      // has no link-speed truth and its drives' motor speed rings with the
      // transmission); stop-and-go samples are taken at rest (the settle
      // criterion held): speed and acceleration 0.
      std::vector<Eigen::Vector3d> omega(out.sim.samples.size(), Eigen::Vector3d::Zero()), tau, alpha;
      // On the fly the twist at a reading follows the torques the drives
      // applied before it (sim/sampling.hpp SampleRecord::tau_last,
      // tau_between), not the torque computed from that reading, which reacts
      // to its quantisation (the model test's noise fitted: on the ideal twin
      // the lag h3 came out at 6 sigma). Samples without that record
      // (stop-and-go, hardware) use the drive torque of the sample and the
      // torque of the sample before.
      const bool torque_history = in_motion && !spec.hardware;
      for (const sim::SampleRecord& r : out.sim.samples) tau.push_back(torque_history ? r.tau_last : r.tau);
      if (torque_history && motion.torque_before)
        for (const sim::SampleRecord& r : out.sim.samples) motion.torque_between.push_back(r.tau_between);
      if (in_motion) {
        const double dt = spec.sim.sampling->sample_every / spec.sim.twin.servo_rate_hz;
        std::vector<double> t;
        for (const sim::SampleRecord& r : out.sim.samples) t.push_back(static_cast<double>(r.id) * dt);
        calib::RateOptions ro;
        ro.alpha_span = std::max(1, static_cast<int>(std::lround(kAccelerationHalfWindow_s / dt)));
        calib::ReadingRates rates = calib::reading_rates(t, problem.theta_m, ro);
        omega = std::move(rates.omega);
        alpha = std::move(rates.alpha);
      }
      // A compliant transmission rings after the drives' start step (the
      // first command jumps from the readings where the robot stands to the
      // controller's home): its twist is not c tau for a few periods; on the
      // fly the first kStartTransient_s of samples are left out (whether the
      // robot's transmissions are compliant or not: the procedure does not know).
      if (in_motion)
        motion.skip_first = static_cast<int>(std::ceil(kStartTransient_s * spec.sim.twin.servo_rate_hz /
                                                       spec.sim.sampling->sample_every));
      calib::LmOptions lo;
      if (spec.calibration.lm_iterations) lo.max_iterations = *spec.calibration.lm_iterations;
      lo.encoder_sigma = out.crb_sigma_rad > 0.0 ? std::optional<double>(out.crb_sigma_rad) : std::nullopt;
      lo.true_xy = &true_xy;
      lo.loss = spec.calibration.loss;
      if (lo.loss.active() && !(lo.loss.scale > 0.0))
        lo.loss.scale = calib::default_tuning(lo.loss.kind) * out.crb_sigma_rad;
      calib::MotionFit fit;
      std::string friction_note, speed_note;
      // The speed over which the drives' friction builds up, chosen by the
      // model test (calib/friction_profile.hpp) at the friction of motion.load.
      const bool fit_speed = in_motion && motion.friction && out.crb_sigma_rad > 0.0;
      const auto choose_speed = [&](const char* at) {
        const calib::FrictionProfile speeds = calib::friction_speed_profile(
            problem, omega, tau, lo, motion, alpha, calib::default_friction_speeds(), out.crb_sigma_rad);
        motion = speeds.model;
        fit = speeds.fit;
        const std::string tried = profile_tried(speeds, "{:.3g}");
        speed_note = fmt::format(
            "drive friction builds up over {:.3g} rad/s (F tanh(omega / v)), the smallest chi2/dof of the speeds "
            "tried in rad/s at {} ({})",
            speeds.scale, at, tried);
      };
      if (fit_speed) choose_speed("the stated friction");
      if (motion.clearance && inputs.drive_friction.fit_scale && out.crb_sigma_rad > 0.0) {
        // The stated friction times the factor the model test prefers.
        calib::FrictionProfile profile = calib::calibrate_friction_profile(
            problem, omega, tau, lo, motion, alpha, calib::default_friction_scales(), out.crb_sigma_rad);
        fit = std::move(profile.fit);
        motion = profile.model;
        const std::string tried = profile_tried(profile, "{:.2f}");
        friction_note = fmt::format(
            "drive friction for the force signs: the stated values x{:.2f} (Coulomb {:.3g}, {:.3g}, {:.3g} N m), the "
            "smallest chi2/dof of the factors tried ({})",
            profile.scale, motion.load.coulomb_Nm[0], motion.load.coulomb_Nm[1], motion.load.coulomb_Nm[2], tried);
        // A speed chosen at a wrong friction stands in for it: chosen again at the factor's.
        if (fit_speed && profile.scale != 1.0) choose_speed("that friction");
      } else if (!fit_speed) {
        fit = calib::calibrate_in_motion(problem, omega, tau, lo, motion, alpha);
      }
      std::string clearance_dropped;
      if (motion.clearance && !spec.calibration.estimate_clearance && !calib::clearance_detected(fit)) {
        // By default the clearance stays in the model only where the data
        // show it: no play 3 sigma from 0, the fit is made again without it
        // (every sample used; the force signs are not needed).
        clearance_dropped = fmt::format(
            "joint clearance not detected (d = {:.2f}, {:.2f}, {:.2f} um, 1-sigma {:.2f}, {:.2f}, {:.2f} um: none 3 "
            "sigma from 0): calibrated without it, from every sample",
            1e3 * fit.clearance[0], 1e3 * fit.clearance[1], 1e3 * fit.clearance[2], 1e3 * fit.clearance_sigma[0],
            1e3 * fit.clearance_sigma[1], 1e3 * fit.clearance_sigma[2]);
        motion.clearance = false;
        fit = calib::calibrate_in_motion(problem, omega, tau, lo, motion, alpha);
      }
      std::string before_dropped;
      if (motion.torque_before && !calib::torque_before_detected(fit)) {
        // Likewise the response to the torque before: kept only where the
        // data show it (some h_i 3 sigma from 0; a rigid or slow transmission has none).
        before_dropped = fmt::format(
            "no response of the twist to the torque before detected (h = {:.3g}, {:.3g}, {:.3g} rad/N m, 1-sigma "
            "{:.2g}, {:.2g}, {:.2g}): calibrated without it",
            fit.torque_before[0], fit.torque_before[1], fit.torque_before[2], fit.torque_before_sigma[0],
            fit.torque_before_sigma[1], fit.torque_before_sigma[2]);
        motion.torque_before = false;
        fit = calib::calibrate_in_motion(problem, omega, tau, lo, motion, alpha);
      }
      std::vector<std::string> drive_notes;
      if (out.crb_sigma_rad > 0.0) {
        // The drive train's effects the data call for, per joint (calib/reading_model_selection.hpp).
        calib::DriveEffectSelection chosen =
            calib::select_drive_effects(problem, omega, tau, lo, motion, alpha, inputs.drive_candidates);
        fit = std::move(chosen.fit);
        motion = chosen.model;
        if (!chosen.kept.empty()) drive_notes.push_back("drive train estimated with the geometry: " + fmt::format("{}", fmt::join(chosen.kept, "; ")));
        if (!chosen.dropped.empty()) drive_notes.push_back("drive train effects not detected: " + fmt::format("{}", fmt::join(chosen.dropped, "; ")));
      }
      if (fit.sandwich_used)
        drive_notes.push_back(fmt::format(
            "the readings exceed the noise (chi2/dof {:.3g} with the reading model): the 1-sigma stated are the "
            "residuals' autocorrelation-robust sandwich, {:.2g}x the noise model's",
            fit.chi2_per_dof, fit.sandwich_inflation));
      out.calibration = fit.result;
      if (!step_note.empty()) out.calibration->notes.push_back(step_note);
      for (std::string& note : drive_notes) out.calibration->notes.push_back(std::move(note));
      out.motion_nu = fit.nu;
      out.motion_nu_sigma = fit.nu_sigma;
      used = fit.corrected;
      if ((motion.clearance || motion.cyclic_prior_rad > 0.0) && out.crb_sigma_rad > 0.0) {
        // With the clearance or the cyclic error carried, the bound of the
        // joint estimation (geometry and nuisance values, the samples the
        // procedure keeps at the truth, the cyclic error's prior).
        // (At the reading noise itself: the cyclic error's prior does not scale with it.)
        out.crb = scaled_bound(
            [&] {
              std::array<double, kNumParams> b =
                  calib::motion_crb(actual.geometry, problem.free, noiseless, omega, tau, motion, alpha, out.crb_sigma_rad);
              for (double& v : b) v /= out.crb_sigma_rad;
              return b;
            },
            out.crb_sigma_rad);
      } else if (fit.kept.size() < noiseless.size()) {
        // The bound of the samples the fit used.
        std::vector<Eigen::Vector3d> kept_noiseless;
        for (std::size_t j : fit.kept) kept_noiseless.push_back(noiseless[j]);
        out.crb = scaled_bound([&] { return calib::crb_sigma(actual.geometry, problem.free, kept_noiseless, 1.0); },
                               out.crb_sigma_rad);
      }
      if (!speed_note.empty()) out.calibration->notes.push_back(speed_note);
      if (!friction_note.empty() && motion.clearance) out.calibration->notes.push_back(friction_note);
      // For the monitor of the operation (run/monitor_run.hpp reading_model_after_calibration).
      if (motion.clearance || !clearance_dropped.empty()) out.joint_play_mm = fit.clearance;
      if (!friction_note.empty() && motion.clearance)
        out.drive_friction_fitted = DriveFriction{motion.load.coulomb_Nm, motion.load.viscous_Nm_s, false};
      if (!clearance_dropped.empty()) out.calibration->notes.push_back(clearance_dropped);
      if (!before_dropped.empty()) out.calibration->notes.push_back(before_dropped);
      if (fit.kept.size() < noiseless.size()) {
        const std::size_t weak = noiseless.size() - fit.kept.size() - static_cast<std::size_t>(motion.skip_first);
        out.calibration->notes.push_back(
            fmt::format("{} of {} samples used: the first {} left out (the drives' start transient)", fit.kept.size(),
                        noiseless.size(), motion.skip_first) +
            (weak > 0 ? fmt::format(", {} where a passive link's force was below {:.2g} N (its sign uncertain)", weak,
                                    fit.tension_min_N)
                      : std::string()));
      }
      out.calibration->notes.push_back(fmt::format(
          "estimated with the geometry: latch skew s2 {:.3g} s, s3 {:.3g} s; transmission compliance "
          "c1 {:.3g}, c2 {:.3g}, c3 {:.3g} rad/N m (0: not excited, e.g. a torque-off joint); friction twist "
          "c F {:.3g}, {:.3g}, {:.3g} rad",
          fit.nu[0], fit.nu[1], fit.nu[2], fit.nu[3], fit.nu[4], fit.friction[0], fit.friction[1], fit.friction[2]));
      if (motion.torque_before)
        out.calibration->notes.push_back(fmt::format(
            "the transmissions' twist also responds to the change of torque since the sample before (the mean drive "
            "torque since it, less the last period's, on the fly): h {:.3g}, "
            "{:.3g}, {:.3g} rad/N m (1-sigma {:.2g}, {:.2g}, {:.2g})",
            fit.torque_before[0], fit.torque_before[1], fit.torque_before[2], fit.torque_before_sigma[0],
            fit.torque_before_sigma[1], fit.torque_before_sigma[2]));
      if (motion.cyclic_prior_rad > 0.0)
        out.calibration->notes.push_back(fmt::format(
            "the encoders' once-per-turn error (data sheet +-{:.2g} rad, random phase) is carried in the 1-sigma and "
            "the Cramer-Rao bound, not estimated",
            motion.cyclic_prior_rad * std::sqrt(2.0)));
      if (motion.clearance)
        out.calibration->notes.push_back(fmt::format(
            "joint clearance estimated with the geometry: passive links act as lb_i +- d_i by the sign of their axial "
            "force, d = {:.2f}, {:.2f}, {:.2f} um (1-sigma {:.2f}, {:.2f}, {:.2f} um; force sign certain in {:.0f}, {:.0f}, "
            "{:.0f} % of the samples)",
            1e3 * fit.clearance[0], 1e3 * fit.clearance[1], 1e3 * fit.clearance[2], 1e3 * fit.clearance_sigma[0],
            1e3 * fit.clearance_sigma[1], 1e3 * fit.clearance_sigma[2], 100 * fit.clearance_used[0],
            100 * fit.clearance_used[1], 100 * fit.clearance_used[2]));
    } else {
      out.calibration = calib::calibrate(problem, mo);
    }
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

  if (out.calibration && out.calibration->cost == calib::Cost::kML && out.crb_sigma_rad > 0.0 &&
      used.size() > problem.free.count()) {
    out.model_test = calib::model_test(out.calibration->geometry, problem.free, used, out.crb_sigma_rad);
    if (!out.model_test->passed) out.calibration->notes.push_back(out.model_test->diagnosis);
  }

  if (out.calibration) {
    for (const Eigen::Vector3d& m : used) {
      double r = NAN;
      const calib::MlResidual residual(m);
      residual(out.calibration->geometry.values.data(), &r);
      out.residual_urad.push_back(r * 1e6);
    }
  }

  if (spec.compensation) {
    // A constant-torque joint preloads the chain for the sampling only; the
    // accuracy test runs the robot as in operation (that joint torque-off).
    sim::TwinConfig test_twin = spec.sim.twin;
    for (sim::ServoDrive& d : test_twin.drives)
      if (d.mode == sim::ServoMode::kTorque) d.mode = sim::ServoMode::kTorqueOff;
    stage("measuring accuracy with the nominal model");
    const unsigned long long seed = sim::derive_seed(spec.sim.seed, 4);
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
      out.after = measure_accuracy(actual, test_twin, out.calibrated, *spec.compensation, seed, "calibrated",
                                 &steps("calibrated model"), spec.sim.max_tracking_mm);
    }
    if (!spec.hardware) {
      stage("measuring accuracy with the actual parameters (the floor)");
      Robot truth = out.nominal;
      truth.geometry = actual.geometry;
      out.floor = measure_accuracy(actual, test_twin, truth, *spec.compensation, seed, "actual",
                                 &steps("actual parameters"), spec.sim.max_tracking_mm);
    }
  }
  if (out.calibration && !spec.hardware) out.positioning = calibrated_positioning(out);
  if (spec.sim.operation) {
    stage("monitoring the operation with the calibrated model");
    out.monitor = monitor_after_calibration(out);
  }
  out.checks = evaluate_expectations(out);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

const std::vector<std::string>& run_output_names() {
  static const std::vector<std::string> names{
      "samples.csv", "trajectory.csv", "model.xml", "actual.yaml", "calibration.yaml", "summary.json",
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
