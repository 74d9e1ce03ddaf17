#include "run/calibration_procedure.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include <fmt/format.h>

#include "calib/chi_square.hpp"
#include "calib/excitation/fisher.hpp"
#include "calib/friction_profile.hpp"
#include "calib/reading_model_selection.hpp"
#include "calib/reading_rates.hpp"
#include "calib/reading_step.hpp"
#include "calib/robust_loss.hpp"
#include "calib/sample_weights.hpp"
#include "models/errors.hpp"
#include "models/samples.hpp"
#include "models/yaml_util.hpp"

namespace gpm::scenario {
namespace {

// On the fly, the joint accelerations are differences of the reading
// speeds over +-this (s; calib/reading_rates.hpp: the speeds are central
// differences over +-1 sample). Noise of 17-bit readings (q = 4.8e-5 rad)
// at a 1 ms sample interval h: q / (sqrt 12 2 h w) = 0.86 rad/s^2 at w = 8 ms,
// against q / (4 sqrt 2 h^2) = 8.5 rad/s^2 at w = h, which made the main job's chi2/dof 1.44
// (8 ms: 1.08; 4 and 12 ms alike; 16 ms failed its 3 CRB sigmas, 4.7).
constexpr double kAccelerationHalfWindow_s = 8e-3;

// The largest chi2/dof at which the speed profile's walk is taken as it is
// (calib/friction_profile.hpp ProfileStart::trust): the main job's speed
// profile is 1.13, 1.09, 1.04, 1.09, 1.21, one minimum; robots the model
// misses (chi2/dof 20 to 2000) can have two.
constexpr double kWalkTrust = 2.0;

// The Wald test's level at which a drive train's effect is kept (calib/reading_model_selection.hpp).
constexpr double kDriveEffectSigmas = 3.0;

// A passive link's force sign is taken as certain beyond this many of the
// force's 1-sigma as the hub's force balance sees it (calib/friction_balance.hpp),
// unless calibration.tension_min_N states the threshold.
constexpr double kForceSignSigmas = 2.0;

// The largest chi2/dof at which the force signs are refined: the samples
// of a passive link crossing its play left out (calibration.crossing_s,
// calib/play_crossing.hpp) and the signs' doubt weighed
// (drive_friction.weigh_signs, calib/sample_weights.hpp). Refinements of the
// clearance model, for a model that fits the readings to about the noise
// (the realistic preset's robots 1.0-1.3); where it misses more (the geared
// robots' drive trains, 5 to 1000) fewer samples or their weights would
// leave the geometry to that misfit.
constexpr double kSignsFitChi2PerDof = 2.0;

// Above kSignsFitChi2PerDof the crossings of the passive links' play are
// left out all the same where the fits without them come within this
// chi2/dof: the crossings were most of the misfit (geared robots whose
// reading model holds their drive train: chi2/dof 12-120 with them, 3-10
// without, seeds 29900-29915); where the drive train's misfit remains
// (25-200 without them) fewer samples would leave the geometry to it.
constexpr double kCrossingsLeftChi2PerDof = 10.0;

// Leaving the crossings out trades samples for fit: where the geometry's
// 1-sigma without them grows beyond this factor they are kept (through a
// drive's noisy torque readings the force signs near zero flip, the windows
// cover most of the samples whose signs are certain: the main job through
// Modbus kept 996 of 8184 samples, its 1-sigma 2.7x, its error 2.4x).
constexpr double kCrossingsLeftSigmaGrowth = 1.5;
// The fit's chi2/dof within which the reducer's error once per joint
// revolution is estimated under the data sheet's prior rather than carried
// (estimate_joint_error): about twice the misfit of a geared robot whose
// effects the model holds but for the torque-off rotor's ringing after a
// knock (the geared basic set: chi2/dof 2.3-5). A larger misfit is an effect
// the model lacks, which a harmonic with a prior 20x the noise takes up
// (every effect drawn, seeds 31100-31119: 3 robots estimated within 10, 2 of
// them worse and parameters up to 9.8 sigma from the truth; none within 6).
constexpr double kJointErrorChi2PerDof = 6.0;
// The share of the misfit above the noise that the reducer's error once per
// joint revolution, estimated, must take away to be kept: residuals
// correlated along the path pass the information criterion and the 3-sigma
// test with a few percent of it where there is no such error (the geared
// basic set, seeds 31100-31119: 2-13 %), and an error that is there takes
// most of it (55-94 % where it was estimated).
constexpr double kJointErrorMisfitShare = 0.5;

// The motion model's fit in progress: the problem, the samples' rates and
// torques, the LM options and the notes each stage leaves.
struct MotionStage {
  calib::Problem problem;
  std::vector<Eigen::Vector3d> omega, tau, alpha;
  std::vector<double> t_s;  // the samples' times (s; on the fly)
  int alpha_span = 0;       // the accelerations' differences span +-this many samples
  calib::LmOptions lo;
  calib::MotionModel motion;
  calib::MotionFit fit;
  double sigma = 0.0;
  std::string balance_note, cogging_note, speed_note, friction_note, clearance_dropped, before_dropped;
  calib::MotionModel candidates;  // the drive train's candidates (measure_load)
  std::optional<calib::BalanceFriction> balance;  // each drive's friction by the hub's force balance
  int balance_taken = 0;  // of its six values, those that replaced the stated (calib::TransmissionLoad)
  std::vector<std::string> drive_notes;  // the drive train's effects kept and dropped, the sandwich
  double friction_scale = 1.0;
};

// "value: chi2/dof" of each value a model-test profile tried (the run's
// notes), the values formatted with value_format.
std::string profile_tried(const calib::FrictionProfile& p, std::string_view value_format) {
  std::string out;
  for (std::size_t k = 0; k < p.scales.size(); ++k)
    out += fmt::format("{}{}: {:.3g}", k ? ", " : "", fmt::format(fmt::runtime(value_format), p.scales[k]), p.chi2_per_dof[k]);
  return out;
}

// Throws InputError unless every per-sample series of s that is given has one entry per reading.
void check_sizes(const SampleSeries& s) {
  const std::size_t n = s.theta_m.size();
  const auto check = [n](std::size_t size, const char* what) {
    if (size != 0 && size != n)
      throw InputError(fmt::format("calibration: {} {} for {} readings (one per reading, or none)", size, what, n));
  };
  check(s.t_s.size(), "times");
  check(s.tau.size(), "drive torques");
  check(s.tau_between.size(), "mean drive torques since the sample before");
}

// The mean interval between samples taken at times t_s (s); 0 for fewer than two.
double sample_period_s(const std::vector<double>& t_s) {
  return t_s.size() < 2 ? 0.0 : (t_s.back() - t_s.front()) / static_cast<double>(t_s.size() - 1);
}

// The joints' speeds and accelerations (rad/s, rad/s^2): on the fly
// differences of the readings themselves (calib/reading_rates.hpp: speeds
// central over +-1 sample, accelerations over +-kAccelerationHalfWindow_s;
// a real robot has no link-speed truth and its drives' motor speed rings with
// the transmission); stop-and-go samples are taken at rest: 0.
void reading_rates_of(const SampleSeries& s, bool in_motion, MotionStage& m) {
  const std::size_t n = s.theta_m.size();
  m.omega.assign(n, Eigen::Vector3d::Zero());
  if (!in_motion) return;
  if (s.t_s.size() != n || n < 2)
    throw InputError("calibration: samples on the fly need the time of each reading (samples.csv column t)");
  const double dt = sample_period_s(s.t_s);
  calib::RateOptions ro;
  ro.alpha_span = std::max(1, static_cast<int>(std::lround(kAccelerationHalfWindow_s / dt)));
  calib::ReadingRates rates = calib::reading_rates(s.t_s, s.theta_m, ro);
  m.omega = std::move(rates.omega);
  m.alpha = std::move(rates.alpha);
  m.alpha_span = ro.alpha_span;
}

// The samples left out at the start on the fly: those within skip_s of the
// first (a compliant transmission rings after the drives' start step, the
// first command jumping from where the robot stands to the controller's
// home: its twist is not c tau for a few periods; left out whether the
// transmissions are compliant or not: the procedure does not know).
int start_transient_count(const std::vector<double>& t_s, double skip_s) {
  int k = 0;
  // 1e-9: a time on the bound (sample id x interval) is not within it.
  while (static_cast<std::size_t>(k) < t_s.size() && t_s[static_cast<std::size_t>(k)] - t_s.front() < skip_s * (1.0 - 1e-9))
    ++k;
  return k;
}

// The stage's LM options from the procedure's options and sigma.
calib::LmOptions lm_options(const ProcedureOptions& o) {
  calib::LmOptions lo;
  lo.max_iterations = o.method.lm_max_iterations;
  lo.encoder_sigma = o.sigma_rad > 0.0 ? std::optional<double>(o.sigma_rad) : std::nullopt;
  lo.loss = o.method.loss;
  if (lo.loss.active() && !(lo.loss.scale > 0.0)) lo.loss.scale = calib::default_tuning(lo.loss.kind) * o.sigma_rad;
  return lo;
}

// Readings taken at their own times carried to joint 1's instant t_1 by their
// rates: theta_m_i(t_1) = theta_m_i + omega_i (t_1 - t_i) (drives polled one
// after another; a lag common to the three moves no reading, and the latch
// skew s_i fits what is left).
void carry_to_joint1_time(const SampleSeries& s, MotionStage& m) {
  if (s.read_lag_s.size() != s.theta_m.size()) return;
  for (std::size_t j = 0; j < s.theta_m.size(); ++j)
    m.problem.theta_m[j] += m.omega[j].cwiseProduct(s.read_lag_s[j]);
}

// The motion stage before any fit: problem, rates, torques (on the fly the
// twist follows the torques the drives applied before the reading, not the
// one computed from it, which reacts to its quantisation), skipped samples.
MotionStage motion_stage(const SampleSeries& s, const CalibrationInputs& in, const ProcedureOptions& o) {
  if (s.tau.size() != s.theta_m.size())
    throw InputError("calibration: estimating compliance, skew or clearance needs the drive torque of each sample "
                     "(samples.csv columns tau_last1..3 or tau1..3)");
  MotionStage m;
  m.t_s = s.t_s;
  m.problem.theta_m = s.theta_m;
  m.problem.true_xy = s.true_xy;
  m.problem.start = o.start;
  m.problem.free = o.free;
  m.motion = in.motion;
  m.sigma = o.sigma_rad;
  m.tau = s.tau;
  if (m.motion.torque_before && !s.tau_between.empty()) m.motion.torque_between = s.tau_between;
  reading_rates_of(s, o.in_motion, m);
  carry_to_joint1_time(s, m);
  if (o.in_motion) m.motion.skip_first = start_transient_count(s.t_s, o.skip_first_s);
  m.lo = lm_options(o);
  return m;
}

// The speed over which the drives' friction builds up, chosen by the model
// test (calib/friction_profile.hpp) at the friction of motion.load; at: the
// friction's name in the note. The speeds tried are those whose friction
// twist the joints' speeds tell from the latch skew (calib::
// speeds_told_from_skew). The profile walks from the speed of known
// (m.fit, made already with m.motion) or from the middle speed; where the
// minimum it finds has chi2/dof above kWalkTrust every speed is fitted (on
// the population's robots whose readings the model misses, chi2/dof has
// more than one minimum over the speeds).
void choose_speed(MotionStage& m, const char* at, const calib::MotionFit* known, double max_skew_correlation) {
  const std::vector<double> all = calib::default_friction_speeds();
  const bool skew = m.motion.skew;
  const std::vector<double> grid = calib::speeds_told_from_skew(all, m.omega, {false, skew, skew}, max_skew_correlation);
  calib::ProfileStart from;
  from.value = known ? m.motion.load.friction_speed_rad_s : grid[grid.size() / 2];
  from.known = known;
  from.walk = true;
  from.trust = kWalkTrust;
  const calib::FrictionProfile speeds =
      calib::friction_speed_profile(m.problem, m.omega, m.tau, m.lo, m.motion, m.alpha, grid, m.sigma, from);
  m.motion = speeds.model;
  m.fit = speeds.fit;
  m.speed_note = fmt::format(
      "drive friction builds up over {:.3g} rad/s (F tanh(omega / v)), the smallest chi2/dof of the speeds "
      "tried in rad/s at {}{} ({}){}",
      speeds.scale, at, speeds.scales.size() < grid.size() ? fmt::format(", walking down from {:.3g}", *from.value) : "",
      profile_tried(speeds, "{:.3g}"),
      grid.size() < all.size() ? fmt::format("; {} of the {} speeds not tried: over these joint speeds their twist is "
                                             "the latch skew's column (correlation above {:g})",
                                             all.size() - grid.size(), all.size(), max_skew_correlation)
                               : "");
}

// What the friction scale multiplies: the stated values, or where the force balance contradicted them its.
std::string friction_source(const MotionStage& m) {
  if (m.balance_taken == 0) return "the stated values";
  return m.balance_taken == 6 ? "the force balance's values" : "the stated values and where they differ the force balance's";
}

// The stated friction times the factor the model test prefers (for the
// clearance's force signs), walking down chi2/dof from the factor 1 (known:
// its fit, when made already with m.motion).
void choose_friction_scale(MotionStage& m, const calib::MotionFit* known) {
  calib::FrictionProfile profile = calib::calibrate_friction_profile(
      m.problem, m.omega, m.tau, m.lo, m.motion, m.alpha, calib::default_friction_scales(), m.sigma,
      calib::ProfileStart{1.0, known, true});
  m.fit = std::move(profile.fit);
  m.motion = profile.model;
  m.friction_scale = profile.scale;
  m.friction_note = fmt::format(
      "drive friction for the force signs: {} x{:.2f} (Coulomb {:.3g}, {:.3g}, {:.3g} N m), the "
      "smallest chi2/dof of the factors tried, walking down from 1 ({})",
      friction_source(m), profile.scale, m.motion.load.coulomb_Nm[0], m.motion.load.coulomb_Nm[1], m.motion.load.coulomb_Nm[2],
      profile_tried(profile, "{:.2f}"));
}

// The stated frictions (one per joint) replaced by the balance's where they
// lie more than kDriveEffectSigmas of its 1-sigma apart (the data sheet
// holds unless the robot's own data contradict it, the test every other
// effect of the procedure passes); the joints (1-based) whose value was taken.
std::vector<int> take_measured(std::array<double, 3>& stated, const std::array<double, 3>& found,
                               const std::array<double, 3>& sigma) {
  std::vector<int> taken;
  for (std::size_t i = 0; i < 3; ++i)
    if (std::abs(found[i] - stated[i]) > kDriveEffectSigmas * sigma[i]) {
      stated[i] = found[i];
      taken.push_back(static_cast<int>(i) + 1);
    }
  return taken;
}

// "joints 1, 3" or "none".
std::string joints(const std::vector<int>& j) { return j.empty() ? "none" : fmt::format("joints {}", fmt::join(j, ", ")); }

// The motors' cogging the force balance found (f; cogging_per_rad = P N)
// added to the drive torques of m where its pair lies kDriveEffectSigmas
// from 0: the torque the transmissions carry is the drive's and the
// cogging's (the clearance's force signs, the backlash's flanks and the
// twist follow it), and on those of a driven joint the twist's harmonic a
// candidate of the reading model; the note says which. True where some
// joint's was added.
bool add_cogging_torque(MotionStage& m, const calib::BalanceFriction& f, double cogging_per_rad) {
  std::vector<std::string> found;
  bool added = false;
  for (int i = 0; i < 3; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const double z = std::hypot(f.cogging_Nm[k] / f.cogging_sigma_Nm[k], f.cogging_Nm[k + 3] / f.cogging_sigma_Nm[k + 3]);
    const double amplitude = std::hypot(f.cogging_Nm[k], f.cogging_Nm[k + 3]);
    found.push_back(fmt::format("joint {} {:.2g} N m ({:.1f} sigma)", i + 1, amplitude, z));
    if (!(z >= calib::pair_sigma_level(kDriveEffectSigmas))) continue;
    found.back() += ", added";
    added = true;
    // A torque-off drive's twist is its compliance times this torque alone: that column is the harmonic.
    const bool torque_off = std::ranges::all_of(m.tau, [i](const Eigen::Vector3d& t) { return t[i] == 0.0; });
    m.candidates.cogging[k] = !torque_off;
    for (std::size_t j = 0; j < m.tau.size(); ++j) {
      const double q = calib::cogging_torque(f, i, m.problem.theta_m[j][i], cogging_per_rad);
      m.tau[j][i] += q;
      if (!m.motion.torque_between.empty()) m.motion.torque_between[j][i] += q;
    }
  }
  m.cogging_note = fmt::format("the motors' cogging ({:g} per motor revolution) from the hub's force balance: {}; "
                               "added to the drive torques where 3 sigma from 0 (the torque the transmissions carry), "
                               "and there on a driven joint a candidate of the reading model",
                               m.motion.cogging_periods, fmt::join(found, ", "));
  return added;
}

// The hub's force balance on m's samples (hub accelerations hub_accel): with
// the motors' cogging where the data sheet states its periods and the
// balance finds it on some joint (add_cogging_torque), else the balance of
// the frictions alone (a model the data do not call for is not taken: its
// columns would move the frictions by their noise).
calib::BalanceFriction balance_with_cogging(MotionStage& m, const CalibrationInputs& in,
                                            const std::vector<Eigen::Vector2d>& hub_accel) {
  const auto balance = [&](double per_rad) {
    return calib::friction_from_force_balance(m.problem.start,
                                              {m.problem.theta_m, m.omega, m.alpha, m.tau, hub_accel, per_rad},
                                              m.motion.load, in.hub_mass_kg, m.motion.skip_first);
  };
  if (std::ranges::any_of(in.drive_candidates.cogging, std::identity{})) {
    const double per_rad = m.motion.cogging_periods * m.motion.gear_ratio;
    calib::BalanceFriction with = balance(per_rad);
    if (add_cogging_torque(m, with, per_rad)) return with;  // else m's torques are as they were
  }
  return balance(0.0);
}

// Each drive's friction from the hub's force balance on the drives' torques
// (calib/friction_balance.hpp), taken in place of a stated value where the
// two differ by more than 3 of the balance's 1-sigma; all stated where the
// balance cannot be made (too few samples away from the singularities); and,
// unless stated, the force signs' threshold from how well the balance knows a
// link's force (kForceSignSigmas). The geometry is the controller's; the hub's
// acceleration is differenced over the readings as the joints' accelerations are.
void friction_from_balance(MotionStage& m, const CalibrationInputs& in) {
  try {
    const std::vector<Eigen::Vector2d> hub_accel =
        calib::hub_accelerations(m.problem.start, m.t_s, m.problem.theta_m, m.alpha_span);
    const calib::BalanceFriction f = balance_with_cogging(m, in, hub_accel);
    const std::vector<int> coulomb = take_measured(m.motion.load.coulomb_Nm, f.coulomb_Nm, f.coulomb_sigma_Nm);
    const std::vector<int> viscous = take_measured(m.motion.load.viscous_Nm_s, f.viscous_Nm_s, f.viscous_sigma_Nm_s);
    m.balance = f;
    m.balance_taken = static_cast<int>(coulomb.size() + viscous.size());
    if (!in.tension_min_stated && f.tension_sigma_N > 0.0) m.motion.tension_min_N = kForceSignSigmas * f.tension_sigma_N;
    m.balance_note = fmt::format(
        "drive friction per joint from the hub's force balance on the drives' torques: Coulomb {:.3g}, {:.3g}, "
        "{:.3g} N m (1-sigma {:.2g}, {:.2g}, {:.2g}), viscous {:.3g}, {:.3g}, {:.3g} N m s/rad (1-sigma {:.2g}, "
        "{:.2g}, {:.2g}; the balance's residual force {:.2g} N RMS over {} samples, a link's force known to {:.2g} N); "
        "taken where 3 sigma from the stated values: Coulomb of {}, viscous of {}{}",
        f.coulomb_Nm[0], f.coulomb_Nm[1], f.coulomb_Nm[2], f.coulomb_sigma_Nm[0], f.coulomb_sigma_Nm[1],
        f.coulomb_sigma_Nm[2], f.viscous_Nm_s[0], f.viscous_Nm_s[1], f.viscous_Nm_s[2], f.viscous_sigma_Nm_s[0],
        f.viscous_sigma_Nm_s[1], f.viscous_sigma_Nm_s[2], f.residual_rms_N, f.samples, f.tension_sigma_N,
        joints(coulomb), joints(viscous),
        in.tension_min_stated ? std::string()
                              : fmt::format("; a passive link's force sign taken as certain above {:.2g} N ({} sigma)",
                                            m.motion.tension_min_N, kForceSignSigmas));
  } catch (const InputError& e) {
    m.balance_note = fmt::format("drive friction as stated, not from the force balance: {}", e.what());
  }
}

// The first fit of the motion model (each drive's friction measured before:
// measure_load): the friction's speed and scale chosen by the model test
// where it can judge them, else one fit.
void fit_motion(MotionStage& m, const CalibrationInputs& in, bool in_motion) {
  const bool fit_speed = in_motion && m.motion.friction && m.sigma > 0.0;
  const double rho = in.drive_friction.max_skew_correlation;
  if (fit_speed) choose_speed(m, m.balance_taken > 0 ? "the friction measured" : "the stated friction", nullptr, rho);
  if (m.motion.clearance && in.drive_friction.fit_scale && m.sigma > 0.0) {
    // The factor 1 is the stated friction: the speed profile's fit when it was made.
    choose_friction_scale(m, fit_speed ? &m.fit : nullptr);
    // A speed chosen at a wrong friction stands in for it: chosen again at the
    // factor's (the factor's fit is the one at the speed it was made with).
    if (fit_speed && m.friction_scale != 1.0) choose_speed(m, "that friction", &m.fit, rho);
  } else if (!fit_speed) {
    m.fit = calib::calibrate_in_motion(m.problem, m.omega, m.tau, m.lo, m.motion, m.alpha);
  }
}

// Each drive's friction from the force balance where it matters (the
// clearance's force signs, the backlash's flanks) and the samples allow it,
// and the motors' cogging it finds; the drive train's candidates are
// in.drive_candidates, a motor's cogging only where the balance found it
// (a harmonic the torques do not show would take up the readings' misfit).
void measure_load(MotionStage& m, const CalibrationInputs& in, bool in_motion) {
  m.candidates = in.drive_candidates;
  m.candidates.cogging = {};
  const bool load_matters = m.motion.clearance || std::ranges::any_of(in.drive_candidates.backlash, std::identity{});
  if (in_motion && in.drive_friction.from_balance && load_matters) friction_from_balance(m, in);
}

// fit_motion with the drive train's harmonic candidates in the model (no
// selection without sigma: without them), or, where that fit diverges (a
// larger effect the model lacks, which they chase), without them.
void first_fit(MotionStage& m, const CalibrationInputs& in, bool in_motion) {
  measure_load(m, in, in_motion);
  if (!(m.sigma > 0.0)) return fit_motion(m, in, in_motion);
  MotionStage without = m;
  m.motion = calib::with_harmonic_candidates(m.motion, m.candidates);
  try {
    fit_motion(m, in, in_motion);
  } catch (const InputError& e) {
    m = std::move(without);
    fit_motion(m, in, in_motion);
    m.drive_notes.push_back(
        fmt::format("the drive train's harmonics left out of the first fit: with them it diverged ({})", e.what()));
  }
}

// The clearance and the lag on the torque before stay in the model only
// where the data show them (some value 3 sigma from 0); else the fit is made
// again without (the clearance's: every sample used, no force signs needed).
void drop_undetected(MotionStage& m, bool keep_clearance) {
  const calib::MotionFit& f = m.fit;
  if (m.motion.clearance && !keep_clearance && !calib::clearance_detected(f)) {
    m.clearance_dropped = fmt::format(
        "joint clearance not detected (d = {:.2f}, {:.2f}, {:.2f} um, 1-sigma {:.2f}, {:.2f}, {:.2f} um: none 3 "
        "sigma from 0): calibrated without it, from every sample",
        1e3 * f.clearance[0], 1e3 * f.clearance[1], 1e3 * f.clearance[2], 1e3 * f.clearance_sigma[0],
        1e3 * f.clearance_sigma[1], 1e3 * f.clearance_sigma[2]);
    m.motion.clearance = false;
    m.fit = calib::calibrate_in_motion(m.problem, m.omega, m.tau, m.lo, m.motion, m.alpha);
  }
  if (m.motion.torque_before && !calib::torque_before_detected(m.fit)) {
    m.before_dropped = fmt::format(
        "no response of the twist to the torque before detected (h = {:.3g}, {:.3g}, {:.3g} rad/N m, 1-sigma "
        "{:.2g}, {:.2g}, {:.2g}): calibrated without it",
        m.fit.torque_before[0], m.fit.torque_before[1], m.fit.torque_before[2], m.fit.torque_before_sigma[0],
        m.fit.torque_before_sigma[1], m.fit.torque_before_sigma[2]);
    m.motion.torque_before = false;
    m.fit = calib::calibrate_in_motion(m.problem, m.omega, m.tau, m.lo, m.motion, m.alpha);
  }
}

// The drive train's effects the data call for, per joint, of m's candidates
// (backlash, errors once and twice per motor revolution, cogging:
// calib/reading_model_selection.hpp).
void select_drive_train(MotionStage& m) {
  if (m.sigma > 0.0) {
    calib::DriveEffectSelection chosen =
        calib::select_drive_effects(m.problem, m.omega, m.tau, m.lo, m.motion, m.alpha, m.candidates,
                                    kDriveEffectSigmas, &m.fit);  // m.fit: the fit of m.motion
    m.fit = std::move(chosen.fit);
    m.motion = chosen.model;
    if (!chosen.kept.empty())
      m.drive_notes.push_back(fmt::format("drive train estimated with the geometry: {}", fmt::join(chosen.kept, "; ")));
    if (!chosen.dropped.empty())
      m.drive_notes.push_back(fmt::format("drive train effects not detected: {}", fmt::join(chosen.dropped, "; ")));
  }
}

// True where some joint's error once per joint revolution in fit lies
// kDriveEffectSigmas from 0, as the drive train's other effects are kept:
// sqrt((a/sa)^2 + (b/sb)^2) above calib::pair_sigma_level (the 1-sigma the misfit's sandwich where the
// residuals exceed the noise; a and b taken as independent).
bool joint_error_detected(const calib::MotionFit& fit) {
  const double level = calib::pair_sigma_level(kDriveEffectSigmas);
  for (std::size_t i = 0; i < 3; ++i) {
    const double za = fit.cyclic[i] / fit.cyclic_sigma[i], zb = fit.cyclic[i + 3] / fit.cyclic_sigma[i + 3];
    if (std::hypot(za, zb) > level) return true;  // NaN (not estimated) compares false
  }
  return false;
}

// On motor encoders behind a reducer the reducer's error once per joint
// revolution (the data sheet's transmission_error_rad) is carried in the
// 1-sigma; it is estimated under that prior instead where the fit with it
// explains the readings (chi2/dof within kJointErrorChi2PerDof) and the
// readings show it (the information criterion, and some joint's error 3
// sigma from 0: residuals correlated along the path pass the criterion
// alone, which counts every sample as independent): over the joints' range of
// motion it is close to the geometry's own directions, and the closure of
// the redundant chain tells them apart only where little else is missed; an
// error that is not there, estimated, takes up what misfit is left. A note
// either way.
void estimate_joint_error(MotionStage& m, const CalibrationInputs& in) {
  const calib::MotionModel& carried = m.motion;
  if (!in.estimate_joint_error || !(m.sigma > 0.0) || !(carried.cyclic_prior_rad > 0.0) || carried.estimate_cyclic) return;
  calib::MotionModel with = carried;
  with.estimate_cyclic = true;
  if (!calib::estimates_reducer_joint_error(with)) return;
  const auto stays_carried = [&m](const std::string& why) {
    m.drive_notes.push_back("the reducer's error once per joint revolution carried in the 1-sigma, not estimated: " +
                            why);
  };
  calib::MotionFit fit;
  try {
    fit = calib::calibrate_in_motion(m.problem, m.omega, m.tau, m.lo, with, m.alpha);
  } catch (const InputError& e) {
    return stays_carried(fmt::format("estimated, the fit diverged ({})", e.what()));
  }
  if (!(fit.chi2_per_dof <= kJointErrorChi2PerDof))
    return stays_carried(fmt::format("estimated it leaves chi2/dof {:.3g} (above {:.3g}), a misfit it would take up",
                                     fit.chi2_per_dof, kJointErrorChi2PerDof));
  // The Bayesian information criterion, the chi-square in units of the
  // misfit left (chi2/dof): ln n per coefficient (a and b of three joints).
  const double gain = (m.fit.chi2 - fit.chi2) / fit.chi2_per_dof;
  const double penalty = 6.0 * std::log(static_cast<double>(fit.kept.size()));
  if (!(gain > penalty))
    return stays_carried(fmt::format("the readings do not show it (estimated, chi2 {:.4g} -> {:.4g}, {:.3g} in units "
                                     "of the misfit left, under the {:.3g} of the information criterion)",
                                     m.fit.chi2, fit.chi2, gain, penalty));
  if (!joint_error_detected(fit))
    return stays_carried(fmt::format("no joint's lies {:g} sigma from 0 (estimated, chi2/dof {:.3g} -> {:.3g})",
                                     kDriveEffectSigmas, m.fit.chi2_per_dof, fit.chi2_per_dof));
  const double share = calib::misfit_share(m.fit.chi2, m.fit.chi2 / m.fit.chi2_per_dof, fit.chi2);
  if (!(share >= kJointErrorMisfitShare))
    return stays_carried(fmt::format("it explains {:.0f} % of the misfit above the noise (chi2 {:.4g} -> {:.4g}), "
                                     "under the {:.0f} % an error that is there explains",
                                     100.0 * share, m.fit.chi2, fit.chi2, 100.0 * kJointErrorMisfitShare));
  m.drive_notes.push_back(fmt::format(
      "the reducer's error once per joint revolution estimated under the data sheet's prior (+-{:.2g} rad): "
      "chi2/dof {:.3g} -> {:.3g} (chi2 {:.4g} -> {:.4g})",
      carried.cyclic_prior_rad * std::sqrt(2.0), m.fit.chi2_per_dof, fit.chi2_per_dof, m.fit.chi2, fit.chi2));
  m.motion = with;
  m.fit = std::move(fit);
}

// The samples a passive link's crossing of its play spans (calibration.
// crossing_s) at the mean period of the samples' times; 0 without times.
int crossing_samples(const SampleSeries& samples, double crossing_s) {
  const double dt = sample_period_s(samples.t_s);
  return crossing_s > 0.0 && dt > 0.0 ? static_cast<int>(std::ceil(crossing_s / dt - 1e-9)) : 0;
}

// The fits of the reading model in motion on samples (its friction, the
// drive train's effects the data call for, the clearance where detected).
MotionStage motion_fits(const SampleSeries& samples, const CalibrationInputs& inputs, const ProcedureOptions& options) {
  MotionStage m = motion_stage(samples, inputs, options);
  // The drive train's harmonic candidates (the errors per motor revolution)
  // are in the model from the first fit on: the friction's speed and scale
  // are chosen by chi2/dof, and a transmission error left out until
  // select_drive_train made those choices on its misfit (0.1 mrad twice per
  // motor revolution: chi2/dof in the hundreds, the friction 1.4x, the
  // clearance's force signs wrong); the selection then drops the harmonics
  // the data do not show. Not the backlash: whether its flank can be told
  // depends on the friction being chosen. No selection without sigma.
  first_fit(m, inputs, options.in_motion);
  drop_undetected(m, options.keep_clearance);
  select_drive_train(m);
  // What looked like a play before the drive train was in the model may be
  // the drive train's (a geared robot with no clearance showed a play at
  // 3 sigma that its harmonics then took): the clearance is judged again.
  drop_undetected(m, options.keep_clearance);
  estimate_joint_error(m, inputs);
  return m;
}

// The geometry's 1-sigma of result, RMS over the free parameters with the
// offsets as the displacement of their elbows (rad x la_i, mm: calib/
// excitation/fisher.hpp parameter_scale); NaN without a covariance.
double geometry_sigma_rms(const calib::Result& result, const FreeMask& free) {
  if (!result.covariance || free.none()) return std::numeric_limits<double>::quiet_NaN();
  const Eigen::VectorXd scale = calib::excitation::parameter_scale(result.geometry, free);
  double sum = 0.0;
  Eigen::Index n = 0;
  for (int k = 0; k < kNumParams; ++k)
    if (free.test(static_cast<size_t>(k))) sum += (*result.covariance)(k, k) * scale[n] * scale[n], ++n;
  return std::sqrt(sum / static_cast<double>(n));
}

// With the clearance in the model and calibration.crossing_s > 0: the fits
// made again with the samples in which a passive link may be crossing its
// play after its force changed sign left out (calib/play_crossing.hpp), from
// the first on (the friction's speed and scale and the drive train are
// chosen on them too), and taken where the model fits the readings within
// kSignsFitChi2PerDof with the crossings, or within kCrossingsLeftChi2PerDof
// without them, and the play is still detected without them (else the fits
// without the play are another model, not the crossings' answer), and the
// geometry's 1-sigma grows by no more than kCrossingsLeftSigmaGrowth; a note
// either way.
void leave_out_crossings(MotionStage& m, const SampleSeries& samples, const CalibrationInputs& inputs,
                         const ProcedureOptions& options) {
  const int crossing = crossing_samples(samples, inputs.crossing_s);
  if (crossing <= 0 || !m.motion.clearance) return;
  CalibrationInputs guarded = inputs;
  guarded.motion.crossing_samples = crossing;
  MotionStage g = motion_fits(samples, guarded, options);
  const double before = m.fit.chi2_per_dof, after = g.fit.chi2_per_dof;
  if (!g.motion.clearance) {  // the play not detected without them: a model of its own, not these samples' question
    m.drive_notes.push_back(fmt::format(
        "the samples of a passive link crossing its play kept: without them the play was not detected (chi2/dof "
        "{:.3g} with them, {:.3g} without the play)",
        before, after));
    return;
  }
  if (!(before > 0.0 && before <= kSignsFitChi2PerDof) && !(after > 0.0 && after <= kCrossingsLeftChi2PerDof)) {
    m.drive_notes.push_back(fmt::format(
        "the samples of a passive link crossing its play kept: chi2/dof {:.3g} with them, {:.3g} without (above {:.3g}): "
        "the model misses more than the crossings",
        before, after, kCrossingsLeftChi2PerDof));
    return;
  }
  const double growth = geometry_sigma_rms(g.fit.result, options.free) / geometry_sigma_rms(m.fit.result, options.free);
  if (growth > kCrossingsLeftSigmaGrowth) {
    m.drive_notes.push_back(fmt::format(
        "the samples of a passive link crossing its play kept: without them {} of {} samples are left and the "
        "geometry's 1-sigma grows {:.2g}x (above {:.2g}x), more than the fit gains (chi2/dof {:.3g} -> {:.3g})",
        g.fit.kept.size(), samples.theta_m.size(), growth, kCrossingsLeftSigmaGrowth, before, after));
    return;
  }
  g.drive_notes.push_back(fmt::format(
      "the {} samples in which a passive link may be crossing its play left out ({:.3g} s after its force changed "
      "sign), the fits made again: chi2/dof {:.3g} -> {:.3g}",
      static_cast<long>(m.fit.kept.size()) - static_cast<long>(g.fit.kept.size()), inputs.crossing_s, before, after));
  m = std::move(g);
}

// With drive_friction.weigh_signs and the clearance in the model: the
// force signs' doubt weighed too (the balance's 1-sigma of a link's force),
// the fit made again, where the model fits the readings within
// kSignsFitChi2PerDof; a note either way.
void weigh_signs(MotionStage& m, const CalibrationInputs& in) {
  if (!in.drive_friction.weigh_signs || !m.motion.clearance || !m.balance || !(m.balance->tension_sigma_N > 0.0)) return;
  const double before = m.fit.chi2_per_dof;
  if (!(before > 0.0 && before <= kSignsFitChi2PerDof)) {
    m.drive_notes.push_back(fmt::format("the force signs' doubt not weighed: chi2/dof {:.3g} above {:.3g}, the model "
                                        "misses more than the signs",
                                        before, kSignsFitChi2PerDof));
    return;
  }
  m.motion.tension_sigma_N = m.balance->tension_sigma_N;
  m.fit = calib::calibrate_in_motion(m.problem, m.omega, m.tau, m.lo, m.motion, m.alpha);
  m.drive_notes.push_back(fmt::format(
      "a passive link's force sign weighs as its doubt allows (the force known to {:.2g} N, and where its joint "
      "may be at rest within the friction it may hold): chi2/dof {:.3g} -> {:.3g}",
      m.balance->tension_sigma_N, before, m.fit.chi2_per_dof));
}

// The note of a covariance widened to the misfit (the sandwich), when it was.
void note_sandwich(MotionStage& m) {
  if (m.fit.sandwich_used)
    m.drive_notes.push_back(fmt::format(
        "the readings exceed the noise (chi2/dof {:.3g} with the reading model): the 1-sigma stated are the "
        "residuals' autocorrelation-robust sandwich, {:.2g}x the noise model's",
        m.fit.chi2_per_dof, m.fit.sandwich_inflation));
}

// The note of the samples the fit used, when it left some out.
std::string samples_used_note(const calib::MotionFit& fit, std::size_t n, int skip_first) {
  const std::size_t weak = n - fit.kept.size() - static_cast<std::size_t>(skip_first);
  return fmt::format("{} of {} samples used: the first {} left out (the drives' start transient)", fit.kept.size(), n,
                     skip_first) +
         (weak > 0 ? fmt::format(", {} where a passive link's force was below {:.2g} N (its sign uncertain)", weak,
                                 fit.tension_min_N)
                   : std::string());
}

// The notes of the values estimated with the geometry (and carried), in the order of gpm run's report.
void estimate_notes(const MotionStage& m, std::vector<std::string>& notes) {
  const calib::MotionFit& f = m.fit;
  notes.push_back(fmt::format(
      "estimated with the geometry: latch skew s2 {:.3g} s, s3 {:.3g} s; transmission compliance "
      "c1 {:.3g}, c2 {:.3g}, c3 {:.3g} rad/N m (0: not excited, e.g. a torque-off joint); friction twist "
      "c F {:.3g}, {:.3g}, {:.3g} rad",
      f.nu[0], f.nu[1], f.nu[2], f.nu[3], f.nu[4], f.friction[0], f.friction[1], f.friction[2]));
  // A 1-sigma the data cannot give (a joint not excited, e.g. torque-off) reads as such, not "nan".
  const auto sigma = [](double v) { return std::isfinite(v) ? fmt::format("{:.2g}", v) : std::string("none: not excited"); };
  if (m.motion.torque_before)
    notes.push_back(fmt::format(
        "the transmissions' twist also responds to the change of torque since the sample before (the mean drive "
        "torque since it, less the last period's, on the fly): h {:.3g}, "
        "{:.3g}, {:.3g} rad/N m (1-sigma {}, {}, {})",
        f.torque_before[0], f.torque_before[1], f.torque_before[2], sigma(f.torque_before_sigma[0]),
        sigma(f.torque_before_sigma[1]), sigma(f.torque_before_sigma[2])));
  if (m.motion.cyclic_prior_rad > 0.0 && !m.motion.estimate_cyclic)
    notes.push_back(fmt::format(
        "the error once per joint revolution (the reducer's transmission error and a direct drive's encoder: data "
        "sheet +-{:.2g} rad, random phase) is carried in the 1-sigma and the Cramer-Rao bound, not estimated",
        m.motion.cyclic_prior_rad * std::sqrt(2.0)));
  else if (m.motion.cyclic_prior_rad > 0.0)
    notes.push_back(fmt::format(
        "the error once per joint revolution ({}) estimated with the geometry under the data sheet's prior: "
        "a sin(theta_m) + b cos(theta_m) with a {:.3g}, {:.3g}, {:.3g}, b {:.3g}, {:.3g}, {:.3g} rad (1-sigma {}, {}, "
        "{}, {}, {}, {})",
        calib::estimates_reducer_joint_error(m.motion) ? "the reducer's" : "the encoders'", f.cyclic[0], f.cyclic[1],
        f.cyclic[2], f.cyclic[3], f.cyclic[4], f.cyclic[5], sigma(f.cyclic_sigma[0]), sigma(f.cyclic_sigma[1]),
        sigma(f.cyclic_sigma[2]), sigma(f.cyclic_sigma[3]), sigma(f.cyclic_sigma[4]), sigma(f.cyclic_sigma[5])));
  if (m.motion.clearance)
    notes.push_back(fmt::format(
        "joint clearance estimated with the geometry: passive links act as lb_i +- d_i by the sign of their axial "
        "force, d = {:.2f}, {:.2f}, {:.2f} um (1-sigma {:.2f}, {:.2f}, {:.2f} um; force sign certain in {:.0f}, {:.0f}, "
        "{:.0f} % of the samples)",
        1e3 * f.clearance[0], 1e3 * f.clearance[1], 1e3 * f.clearance[2], 1e3 * f.clearance_sigma[0],
        1e3 * f.clearance_sigma[1], 1e3 * f.clearance_sigma[2], 100 * f.clearance_used[0],
        100 * f.clearance_used[1], 100 * f.clearance_used[2]));
}

// The outcome of a finished motion stage: result, notes, readings used, the bound's inputs.
CalibrationOutcome motion_outcome(MotionStage&& m, const calib::ReadingModel& stated) {
  CalibrationOutcome out;
  out.with_effects = true;
  out.result = m.fit.result;
  out.used = m.fit.corrected;
  std::vector<std::string>& notes = out.result.notes;
  if (!m.balance_note.empty()) notes.push_back(m.balance_note);
  if (!m.cogging_note.empty()) notes.push_back(m.cogging_note);
  if (!m.speed_note.empty()) notes.push_back(m.speed_note);
  if (!m.friction_note.empty() && m.motion.clearance) notes.push_back(m.friction_note);
  // For the monitor of the operation (run/monitor_run.hpp reading_model_after_calibration).
  out.reading = estimated_reading_model(stated, m.fit, m.motion, m.motion.clearance || !m.clearance_dropped.empty(),
                                        (!m.friction_note.empty() && m.motion.clearance) ||
                                            m.balance_taken > 0);
  if (!m.clearance_dropped.empty()) notes.push_back(m.clearance_dropped);
  if (!m.before_dropped.empty()) notes.push_back(m.before_dropped);
  for (const std::string& note : m.drive_notes) notes.push_back(note);
  const std::size_t n = m.problem.theta_m.size();
  if (m.fit.kept.size() < n) notes.push_back(samples_used_note(m.fit, n, m.motion.skip_first));
  estimate_notes(m, notes);
  out.friction_balance = m.balance;
  out.fit = std::move(m.fit);
  out.motion = std::move(m.motion);
  out.omega = std::move(m.omega);
  out.tau = std::move(m.tau);
  out.alpha = std::move(m.alpha);
  return out;
}

// The static fit (calib/calibrate.hpp) of the readings as they are.
CalibrationOutcome static_outcome(const SampleSeries& s, const ProcedureOptions& o) {
  calib::Problem problem;
  problem.theta_m = s.theta_m;
  problem.true_xy = s.true_xy;
  problem.start = o.start;
  problem.free = o.free;
  CalibrationOutcome out;
  out.result = calib::calibrate(problem, o.method);
  out.used = s.theta_m;
  return out;
}

// What the failed model test t adds of the reading effects the motion model
// left out (calib::left_out_effects): the ones the residuals call for, each
// with its share of the chi-square above the noise, or that none does.
std::string left_out_sentence(const std::vector<calib::LeftOutEffect>& left_out, const calib::ModelTest& t) {
  if (left_out.empty())
    return "; no reading effect the motion model leaves out accounts for it (each one's score test at p < 0.001)";
  const double excess = std::max(t.chi2 - t.dof, 1.0);
  std::string s = "; of the reading effects the motion model leaves out, the residuals call for ";
  const std::size_t shown = std::min<std::size_t>(left_out.size(), 3);
  for (std::size_t k = 0; k < shown; ++k) {
    const calib::LeftOutEffect& e = left_out[k];
    s += fmt::format("{}{} (chi2 down by {:.0f}, {:.0f} % of the {:.0f} above the noise)",
                     k == 0 ? "" : (k + 1 == shown ? " and " : ", "), e.name, e.chi2_drop,
                     100.0 * e.chi2_drop / excess, excess);
  }
  return s;
}

// On the fly with drive_friction.weigh_rest: the speed below which a rotor
// may rest, where its reading moves less than a step q per sample
// (calib/sample_weights.hpp), into inputs.motion, and a note saying so.
void set_stick_speed(const SampleSeries& samples, double q, CalibrationInputs& inputs, std::vector<std::string>& notes) {
  if (!inputs.drive_friction.weigh_rest || samples.t_s.size() < 2) return;
  inputs.motion.stick_speed_rad_s = calib::stick_speed(q, sample_period_s(samples.t_s));
  if (inputs.motion.stick_speed_rad_s > 0.0)
    notes.push_back(fmt::format(
        "a joint slower than {:.3g} rad/s (a reading step per sample) may be at rest, its friction twist then "
        "known within +-c F only: such samples weigh less in the fit (the model test judges them unweighted)",
        inputs.motion.stick_speed_rad_s));
}

}  // namespace

CalibrationOutcome calibrate_samples(const SampleSeries& samples, const CalibrationInputs& inputs_stated,
                                     const ProcedureOptions& options_in) {
  check_sizes(samples);
  ProcedureOptions options = options_in;
  CalibrationInputs inputs = inputs_stated;
  std::vector<std::string> step_notes;
  // Single readings on the fly show their encoders' step (calib/reading_step.hpp):
  // a geared drive's motor encoder is finer at the joint than its bits say,
  // one that turns with the joint is not.
  const std::optional<double> q = options.in_motion ? calib::reading_step(samples.theta_m) : std::nullopt;
  if (q && options.sigma_from_step) {
    options.sigma_rad = calib::reading_sigma(*q, options.reading_noise_rad);
    step_notes.push_back(fmt::format("reading resolution from the samples: {:.4g} rad ({:.4g} counts per joint "
                                     "revolution), reading 1-sigma {:.3g} rad",
                                     *q, 2.0 * M_PI / *q, options.sigma_rad));
  }
  if (q)
    if (std::optional<std::string> note = encoder_turns_with_joint(inputs, *q)) step_notes.push_back(std::move(*note));
  if (q && options.in_motion) set_stick_speed(samples, *q, inputs, step_notes);
  const calib::MotionModel& model = inputs.motion;
  const bool with_effects = model.compliance || model.skew || model.clearance;
  if (with_effects && (options.method.method != calib::Method::kLM || options.method.cost != calib::Cost::kML))
    throw InputError("calibration: estimating compliance, skew or clearance with the geometry needs the method lm "
                     "with the cost ml");
  CalibrationOutcome out;
  calib::Problem fitted;  // with effects: the motion fit's problem (its readings carried to joint 1's instant)
  if (with_effects) {
    MotionStage m = motion_fits(samples, inputs, options);
    leave_out_crossings(m, samples, inputs, options);
    weigh_signs(m, inputs);
    note_sandwich(m);
    fitted = m.problem;
    out = motion_outcome(std::move(m), inputs.monitor.reading);
    if (options.home)
      if (const auto moved = calib::offsets_at_home(*options.home, calib::reducer_errors(out.fit, out.motion),
                                                    out.motion.gear_ratio, out.result, out.used,
                                                    out.reading ? &*out.reading : nullptr))
        out.result.notes.push_back(calib::offsets_at_home_note(*moved));
  } else {
    out = static_outcome(samples, options);
  }
  out.sigma_rad = options.sigma_rad;
  out.result.notes.insert(out.result.notes.begin(), step_notes.begin(), step_notes.end());
  const bool tested_cost = options.test_any_cost || out.result.cost == calib::Cost::kML;
  if (tested_cost && options.sigma_rad > 0.0 && out.used.size() > options.free.count()) {
    // Judged by the encoders' noise alone, unweighted: the samples' weights
    // (the friction's doubt) make the estimate efficient, not the test
    // lenient; the test expects only what that doubt adds on average.
    out.model_test = calib::model_test(out.result.geometry, options.free, out.used, options.sigma_rad, 0.01,
                                       with_effects ? out.fit.carried_chi2 : 0.0,
                                       with_effects ? out.fit.doubt : calib::SampleDoubt{});
    if (out.model_test->carried_chi2 > 0.0)
      out.result.notes.push_back(fmt::format(
          "the model test weighs chi2 less {:.3g} of it, what the error once per joint revolution carried within its "
          "prior explains (the marginal test)",
          out.model_test->carried_chi2));
    if (out.model_test->doubt_chi2 > 0.0)
      out.result.notes.push_back(fmt::format(
          "the model test expects {:.3g} more of chi2 than its degrees of freedom: what the twist of a joint that may "
          "rest adds on average, within +-c F of the data sheet's compliance and the drives' friction (it sums the "
          "residuals unweighted)",
          out.model_test->doubt_chi2));
    if (!out.model_test->passed) {
      if (with_effects) {
        // Only when the test fails: the score tests are of the effects its misfit may need.
        const std::vector<calib::LeftOutEffect> left_out =
            calib::left_out_effects(fitted, out.omega, out.tau, out.motion, out.fit, options.sigma_rad, out.alpha);
        out.model_test->diagnosis += left_out_sentence(left_out, *out.model_test);
        for (const calib::LeftOutEffect& e : left_out) out.model_test->calls_for.push_back(e.name);
      }
      out.result.notes.push_back(out.model_test->diagnosis);
    }
  }
  return out;
}

calib::ReadingModel estimated_reading_model(calib::ReadingModel r, const calib::MotionFit& f,
                                            const calib::MotionModel& motion, bool play_looked_for,
                                            bool friction_measured) {
  const auto estimated = [](double sd) { return std::isfinite(sd) && sd > 0.0; };
  if (estimated(f.nu_sigma[0]) || estimated(f.nu_sigma[1])) r.skew_s = {0.0, f.nu[0], f.nu[1]};
  for (std::size_t i = 0; i < 3; ++i) {
    if (estimated(f.nu_sigma[2 + i])) r.compliance_rad_per_Nm[i] = std::max(0.0, f.nu[2 + i]);
    if (play_looked_for) r.clearance_mm[i] = std::max(0.0, f.clearance[i]);
    if (estimated(f.backlash_sigma[i])) r.backlash_rad[i] = std::max(0.0, f.backlash[i]);
  }
  if (friction_measured) {
    r.load.coulomb_Nm = motion.load.coulomb_Nm;
    r.load.viscous_Nm_s = motion.load.viscous_Nm_s;
  }
  r.harmonic = f.harmonic;
  // The reducer's error once per joint revolution, where it was estimated (0 elsewhere).
  const std::array<double, 6> joint_error = calib::reducer_errors(f, motion).h[calib::kJointHarmonic];
  for (std::size_t k = 0; k < 6; ++k) r.harmonic[calib::kJointHarmonic][k] += joint_error[k];
  r.gear_ratio = motion.gear_ratio;
  r.cogging_periods = motion.cogging_periods;
  return r;
}

SampleSeries sample_series(const Samples& samples) {
  SampleSeries s;
  s.theta_m = samples.theta_m;
  s.t_s = samples.t;
  s.tau = samples.tau_last.empty() ? samples.tau : samples.tau_last;
  s.tau_between = samples.tau_between;
  for (const Eigen::Vector3d& t_read : samples.t_read)
    s.read_lag_s.push_back(Eigen::Vector3d::Constant(t_read[0]) - t_read);
  if (samples.has_xy) s.true_xy = samples.xy;
  return s;
}

bool taken_on_the_fly(const Samples& samples) {
  const std::size_t n = samples.size();
  if (n < 3 || samples.t.size() != n || samples.tau_last.size() != n || samples.tau_between.size() != n) return false;
  const double dt = (samples.t.back() - samples.t.front()) / static_cast<double>(n - 1);
  for (std::size_t j = 1; j < n; ++j)
    if (std::abs(samples.t[j] - samples.t[j - 1] - dt) > 1e-6 * dt) return false;
  return true;
}

FileProcedure samples_file_procedure(const Samples& samples, const Robot& robot, const Geometry& start,
                                     const FreeMask& free, const calib::MethodOptions& method,
                                     std::optional<int> encoder_bits, bool static_model) {
  const int bits = encoder_bits.value_or(robot.data_sheet.encoder_bits);
  const bool on_the_fly = taken_on_the_fly(samples);
  const bool lm_ml = method.method == calib::Method::kLM && method.cost == calib::Cost::kML;
  const bool in_motion = on_the_fly && lm_ml && !static_model;
  FileProcedure p;
  p.motion_not_used = on_the_fly && !lm_ml && !static_model;
  p.options.start = start;
  p.options.free = free;
  p.options.sigma_rad = method.encoder_sigma.value_or(calib::reading_sigma(calib::encoder_step_rad(bits), 0.0));
  p.options.in_motion = in_motion;
  p.options.sigma_from_step = !method.encoder_sigma.has_value();
  p.options.test_any_cost = true;
  p.options.method = method;
  p.options.home = calib::HomePose{robot.home, robot.branch};
  CalibrationSpec c;
  c.drive_friction = stated_drive_friction(robot.data_sheet);
  p.inputs = calibration_inputs(c, robot, in_motion, bits, p.options.sigma_rad);
  p.sigma_stated = method.encoder_sigma.has_value() || in_motion;
  p.model = in_motion ? "the motion model (samples on the fly: compliance, latch skew, friction, clearance)"
                      : "the static model";
  return p;
}

std::string model_test_line(const calib::ModelTest& test, bool stated) {
  const double ratio = test.chi2 / test.dof;
  if (test.passed)
    return fmt::format("model test passes (chi2/dof {:.3g}, p {:.3g}): the residuals agree with the reading 1-sigma "
                       "{:.3g} rad",
                       ratio, test.p_value, test.sigma_rad);
  if (stated)
    return fmt::format("model test fails (chi2/dof {:.3g}, p {:.3g}): the stated 1-sigma understates the error (the "
                       "residuals are {:.3g}x the reading 1-sigma {:.3g} rad)",
                       ratio, test.p_value, test.rms_ratio, test.sigma_rad);
  return fmt::format("model test fails (chi2/dof {:.3g}, p {:.3g}): the readings scatter {:.3g}x the encoders' 1-sigma "
                     "{:.3g} rad; the 1-sigma of the result is scaled by the residuals, an effect the model leaves out "
                     "is not in it",
                     ratio, test.p_value, test.rms_ratio, test.sigma_rad);
}

std::string model_test_yaml(const calib::ModelTest& test, int indent) {
  // Flat keys: a result file stays a robot file, whose diagnostics are one-line values.
  const std::string p(static_cast<std::size_t>(indent), ' ');
  std::string out;
  out += fmt::format("{}model_test_chi2: {}\n", p, format_exact(test.chi2));
  out += fmt::format("{}model_test_dof: {}\n", p, format_exact(test.dof));
  out += fmt::format("{}model_test_chi2_per_dof: {}\n", p, format_exact(test.chi2 / test.dof));
  out += fmt::format("{}model_test_p_value: {}\n", p, format_exact(test.p_value));
  if (test.carried_chi2 > 0.0) out += fmt::format("{}model_test_carried_chi2: {}\n", p, format_exact(test.carried_chi2));
  if (test.doubt_chi2 > 0.0) out += fmt::format("{}model_test_doubt_chi2: {}\n", p, format_exact(test.doubt_chi2));
  out += fmt::format("{}model_test_sigma_rad: {}\n", p, format_exact(test.sigma_rad));
  out += fmt::format("{}model_test_passed: {}\n", p, test.passed ? "true" : "false");
  if (!test.passed) {
    std::string quoted;  // a YAML (and JSON) double-quoted scalar
    for (char c : test.diagnosis) quoted += (c == '"' || c == '\\') ? std::string{'\\', c} : std::string{c};
    out += fmt::format("{}model_test_diagnosis: \"{}\"\n", p, quoted);
  }
  return out;
}

}  // namespace gpm::scenario
