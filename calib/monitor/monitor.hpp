// Drift monitoring during normal operation (issue 17): a controller calls
// monitor_step() every servo cycle with the three encoder readings. The
// monitor
//   - tests for a change with two statistics on the normalised ML
//     innovations z = r / sqrt(sigma^2 + h P h') (r the ML residual of
//     calib/residuals.hpp at the current estimate, h its gradient with
//     respect to the estimated parameters, P their covariance): a
//     sliding-window chi-square (any change) and a generalised likelihood
//     ratio for a step in one estimated parameter from any onset in the
//     window (matched to that parameter's signature, so far more sensitive
//     where the step shows weakly); thresholds from a stated false-alarm
//     rate, shared by the two tests (README.md derives them). The
//     filter below runs one window behind the test (a sample updates it when
//     it leaves the window), so a change inside the window is tested against
//     an estimate that has not absorbed it;
//   - explains an alarm by the single parameter (and onset) whose sensitivity
//     column best fits the window's innovations;
//   - tracks slow drift with an extended Kalman filter over the estimated
//     parameters and a common thermal growth rate of the links (a smooth
//     drift: the rate is a random walk set from the thermal time constant;
//     each parameter also has a small random walk of its own), which updates
//     only the directions the motion observes.
// MuJoCo-style split: MonitorModel is constant, MonitorData mutable;
// monitor_step() allocates nothing.
#pragma once

#include <array>
#include <string>

#include <Eigen/Core>

#include "calib/monitor/learning.hpp"
#include "calib/monitor/ml_sensitivity.hpp"
#include "calib/passive_tension.hpp"
#include "calib/reading_model.hpp"
#include "models/parameters.hpp"

namespace gpm::calib::monitor {

// Most samples held (the change-test window plus the samples gathered for an
// alarm's explanation) and the number of alarms kept.
inline constexpr int kMaxWindow = 512;
inline constexpr int kMaxAlarms = 64;
// Most innovations the learning phase keeps (10 s at 200 samples/s).
inline constexpr int kMaxLearn = 2048;
inline constexpr int kMaxLearnBatches = 128;  // learning batches whose step-test sums are kept
// Filter coordinates: the estimated parameters, the common thermal growth
// rate, the two coefficients of each encoder's once-per-revolution error and
// the effective clearance of each chain.
inline constexpr int kNumCyclic = 6;
inline constexpr int kMaxState = kNumParams + 1 + kNumCyclic + 3;
using StateMatrix = Eigen::Matrix<double, kMaxState, kMaxState>;

// What the user states; make_monitor_model() checks it and derives the rest.
struct MonitorSettings {
  Geometry geometry = Geometry::gpm2002_nominal();  // the calibrated robot (controller's model)
  FreeMask estimate = default_free_mask();          // parameters tracked and used to explain
  // Prior 1-sigma of each estimated parameter around `geometry` (mm or rad);
  // NaN: 0.002 mm for lengths and base coordinates, 2e-5 rad for offsets
  // (pass the calibration's 1-sigma when known).
  std::array<double, kNumParams> prior_sigma = nan_array();
  double cycle_hz = 1000.0;     // servo rate at which monitor_step() is called
  int decimation = 5;           // at most one accepted sample per this many cycles
  double min_motion_counts = 2.0;  // every joint must move this many counts between accepted samples
  int window = 250;             // change-test window W (accepted samples)
  // The step test's shortest step: onsets with at least this many accepted
  // samples from them on (a slip persists; one sample off is no step).
  int step_min_samples = 10;
  // The step test takes each innovation at most this far from 0 (z units):
  // a step is many moderate innovations, a reading glitch or a point where
  // the reading model fails one gross one (Huber-like). 0: no clipping.
  double step_clip = 5.0;
  // The step test's share of the filter's error (explain.hpp step_statistic):
  // false, S_hh^2 P_ii (as if the filter erred along parameter i alone);
  // true, the smaller of that and the Cauchy-Schwarz bound of any error.
  bool step_shared_bound = true;
  // After a learning phase, each step factor goes on learning from the
  // batches of operation (MonitorData::step_terms): it narrows as they add
  // up (its widening by its own uncertainty shrinks) or widens where the
  // robot errs more than it did while learning. false: the learnt factors stay.
  bool refine_step_factors = true;
  // Accepted samples after the crossing before the alarm is explained (the
  // filter waits meanwhile); window + explain_samples <= kMaxWindow.
  int explain_samples = 240;
  double false_alarms_per_hour = 0.01;  // stated false-alarm rate of the change test
  double thermal_tau_s = 60.0;  // time constant of thermal drift; alarms are for faster changes
  // Common thermal growth of the links over one time constant (mm, for a
  // link of the mean length; each link grows in proportion to its length):
  // the growth rate is of order thermal_growth_mm / thermal_tau_s and changes
  // by that much over one time constant. 0: no growth-rate state.
  double thermal_growth_mm = 0.05;
  double length_drift_mm = 0.0;     // independent drift of a length / base coordinate per time constant
  double offset_drift_rad = 2e-6;   // independent drift of an encoder offset per time constant
  // Typical size of a sudden change, the prior of the alarm's explanation
  // (calib/monitor/explain.hpp): an encoder slip, a knock on a link or base.
  double jump_offset_rad = 1e-3;
  double jump_length_mm = 0.005;
  // The reading model (calib/reading_model.hpp) the monitor tests the link
  // angles by: calib::link_angle of each reading at the joint (motor) speed
  // omega passed to monitor_step() and the torque the transmission carries,
  // tau_t = tau - coulomb tanh(omega / friction_speed) - viscous omega
  // (calib::transmitted_torque without the inertia term: the monitor is given
  // no acceleration), and the backlash on the flank of tau_t. Its encoder
  // gives the reading noise; each encoder's once-per-revolution error of
  // amplitude cyclic_rad_i and unknown phase is estimated by the filter
  // (a_i, b_i, prior variance A_i^2 / 2 each); with a clearance d_i the filter
  // estimates each passive link's effective play (prior: the stated value,
  // 1-sigma a quarter of it), the link acting as lb_i + d_i sgn(T_i), T_i from
  // the active link's moment balance (calib/passive_tension.hpp).
  ReadingModel reading = {.load = {.friction_speed_rad_s = 0.1}};
  // Under friction_stick_rad_s the Coulomb friction lies anywhere in
  // +-coulomb: a sample is used only when every joint whose friction twist
  // compliance x coulomb exceeds half the reading noise moves faster.
  double friction_stick_rad_s = 0.05;
  // A sample is used only when |T_i| >= tension_min_N for every chain with a
  // clearance (below it the sign of the force is uncertain).
  double tension_min_N = 0.3;
  // Learning phase (issue 31, learning.hpp): for the first learning_s seconds
  // of operation (from the first call), and the review of its samples after
  // them (README.md: a replay of the samples of its last three quarters
  // through a copy of the filter as learning ends, on the cycles without a
  // live sample), no alarm is raised; the monitor learns from the replayed
  // innovations their scale (robust, never below scale_floor x the stated
  // one), their bias and how alike neighbouring samples are (batches of
  // learning_batch samples, 16..512), and from then
  // on its filter takes the learnt scale as the reading noise and its tests
  // widen by what it learnt (never narrower than the stated model's). The
  // stated clearance, known only as a bound, starts the filter at half its
  // value with a 1-sigma of half of it. The bias is then followed with time
  // constant bias_tau_s (while no alarm is pending). learning_s 0: no
  // learning, the stated model is taken as exact (the monitor before issue 31).
  double learning_s = 8.0;
  int learning_batch = 50;
  double bias_tau_s = 60.0;
  double scale_floor = 1.0;
  // Configuration map (config_map.hpp): with map_radius_rad > 0 the learning
  // phase keeps its residuals over the link angles, and after it a sample is
  // tested on its residual less the learnt one at the same configuration and
  // direction of motion (matched within map_radius_rad of link-angle
  // distance; consecutive learnt samples closer than map_pass_gap_s in time
  // are one pass). A sample with no learnt configuration within the radius
  // is not tested (counted in MonitorData::unmapped). When fewer than
  // 4 x learning_batch of the learnt samples (last three quarters) find
  // another pass's sample within the radius (a job that does not repeat
  // within the learning phase), the map is not used. With the map the
  // learnt scale is at least sqrt(2) scale_floor (a tested residual is the
  // difference of two readings). When `window` consecutive samples after
  // learning find no learnt configuration (the job changed), the monitor
  // learns again from there (MonitorData::relearnings). 0: no map.
  double map_radius_rad = 3e-3;
  double map_pass_gap_s = 0.05;

  // An array of NaN (the "use the default" marker of prior_sigma).
  static std::array<double, kNumParams> nan_array();
};

// Constant model of the monitor (derived once from the settings).
struct MonitorModel {
  MonitorSettings settings;
  double sigma_rad = 0.0;        // reading noise: calib::reading_sigma of settings.reading
  double motion_gate_rad = 0.0;  // min_motion_counts * count (or * noise_rad when ideal)
  double tests_per_hour = 0.0;   // 3600 * cycle_hz / decimation: the most window tests per hour
  double p_window = 0.0;         // false-alarm probability per test sample: rate / tests_per_hour
  double threshold = 0.0;        // chi-square test: chi2_W upper quantile at p_window / 2
  double glr_threshold = 0.0;    // step test: chi2_1 upper quantile at p_window / (2 n_free W)
  double chi_normal_quantile = 0.0;  // the standard normal quantile whose Wilson-Hilferty image at W is `threshold`
  int n_free = 0;                        // number of estimated parameters
  int n_state = 0;                       // filter coordinates: n_free, plus 1 with a growth-rate state
  int rate_index = -1;                   // index of the growth-rate coordinate, -1 without
  int cyclic_index = -1;                 // first of the kNumCyclic cyclic-error coordinates, -1 without
  bool has_clearance = false;            // some reading.clearance_mm > 0: the passive lengths follow the tension
  int clearance_index = -1;              // first of the 3 effective-clearance coordinates, -1 without
  std::array<int, kNumParams> free_index{};  // parameter of each filter coordinate (first n_free)
  // Filter coordinates u = scale * value: 1 for mm, the mean active length
  // (mm) for offsets and cyclic coefficients, so that P is well scaled; the
  // rate is in mm/s.
  std::array<double, kMaxState> scale{};
  std::array<double, kMaxState> growth{};        // d u_k / d (common growth, mm): L_i / mean L for links, else 0
  std::array<double, kMaxState> drift_rate{};    // independent random-walk variance per second of u_k
  double rate_noise = 0.0;                       // random-walk variance per second of the growth rate
  std::array<double, kMaxState> variance_cap{};  // ceiling of each variance
  std::array<double, kMaxState> prior_variance{};  // initial variance
};

// Builds the model; throws gpm::InputError naming the setting that is wrong.
MonitorModel make_monitor_model(const MonitorSettings& settings);

// Which test raised an alarm.
enum class AlarmKind { kChiSquare, kStep };

// "chi_square" or "step".
const char* alarm_kind_name(AlarmKind kind);

// One alarm of the change test.
struct Alarm {
  AlarmKind kind = AlarmKind::kChiSquare;
  double t_s = 0.0;        // time of the sample that crossed the threshold
  double statistic = 0.0;  // window sum of z^2, or the step test's max S_zh^2 / S_hh
  double threshold = 0.0;
  int param = -1;          // parameter whose single change best explains the window
  double delta = 0.0;      // its estimated change (mm or rad)
  double onset_s = 0.0;    // estimated time the change began (first sample it explains)
  double explained = 0.0;  // fraction of the post-onset sum of z^2 that the change explains
  double score = 0.0;      // log evidence of the explanation against no change (explain.hpp)
  double explained_s = 0.0;  // time the explanation was made (explain_samples after t_s)
};

// The drift filter's state: estimate, covariance and what it has absorbed.
struct DriftFilter {
  Geometry estimate;  // current parameter estimate (fixed ones at the model's values)
  // Estimated cyclic encoder error (rad): a_1, b_1, a_2, b_2, a_3, b_3; the
  // reading error of encoder i is a_i sin(theta_m_i) + b_i cos(theta_m_i).
  std::array<double, kNumCyclic> cyclic{};
  std::array<double, 3> clearance{};  // estimated effective play d_i of each chain (mm)
  double growth_rate = 0.0;  // estimated common growth rate (mm/s for a link of the mean length)
  StateMatrix P;             // covariance of the filter coordinates (n_state x n_state used)
  double t_last_update = 0.0;
  long filtered = 0;         // samples the filter has absorbed
  double noise_scale = 1.0;  // the filter's reading noise is noise_scale x model.sigma_rad
};

// The drift filter and its change-test window: the state the filter's
// functions (drift_filter.hpp) and the step test (explain.hpp) work on; the
// monitor holds one, and a second one replays the learning phase's samples
// when learning ends (MonitorData::review).
struct FilterWindow : DriftFilter {
  // Samples not yet in the filter (ring buffer): the change-test window, plus
  // while an alarm is pending the samples since; innovations z, their
  // sensitivities dz/dparams, times and readings (for the filter update when
  // a sample leaves).
  std::array<double, kMaxWindow> z{};
  std::array<double, kMaxWindow> t{};
  std::array<ParamRow, kMaxWindow> dz{};
  std::array<Eigen::Vector3d, kMaxWindow> theta{};
  std::array<Eigen::Vector3d, kMaxWindow> tension{};  // sign of each passive link's axial force (+-1, 0 without clearance)
  std::array<double, kMaxWindow> r_map{};  // the learnt residual taken off each sample (rad; 0 without the map)
  // The filter's share of each innovation's standard deviation, sqrt(h P h') in
  // z units: all samples of a window share the filter's error (the step test).
  std::array<double, kMaxWindow> z_filter{};
  int head = 0;   // next slot to write
  int count = 0;  // samples held
  // The step test's variance factor of each parameter (>= 1; 1 until learnt):
  // its statistic along parameter i is divided by step_factor[i].
  ParamRow step_factor = ParamRow::Ones();
};

// kMaxLearnBatches rows of zeros.
inline std::array<ParamRow, kMaxLearnBatches> zero_batch_rows() {
  std::array<ParamRow, kMaxLearnBatches> rows;
  rows.fill(ParamRow::Zero());
  return rows;
}

// What the review's replay of the learnt samples sums, for the step and
// chi-square tests' factors (learning.hpp); a fresh one is all zeros.
struct LearningSums {
  // Per learning batch and estimated parameter: sums of dz, dz z and dz^2
  // (learning.hpp MatchedBatch).
  std::array<ParamRow, kMaxLearnBatches> h = zero_batch_rows(), hz = zero_batch_rows(), hh = zero_batch_rows();
  // The largest step-test term of each parameter and the largest chi-square
  // statistic of the replay (last three quarters, full windows).
  ParamRow step_max = ParamRow::Zero();
  double chi_max = 0.0;
};

// Mutable state of the monitor.
struct MonitorData : FilterWindow {
  Eigen::Vector3d last_accepted = Eigen::Vector3d::Zero();
  bool has_accepted = false;
  long cycles_since_accepted = 0;
  double statistic = 0.0;  // latest window sum of z^2 (0 until the window is full)
  double step_statistic = 0.0;  // latest step statistic (0 until the window is full)
  double last_z = 0.0;     // latest innovation
  std::array<Alarm, kMaxAlarms> alarms{};  // alarm k is at alarms[k % kMaxAlarms]
  long alarm_count = 0;
  int pending = -1;  // accepted samples until the latest alarm is explained; -1: none pending
  long cycles = 0, accepted = 0, skipped = 0;  // skipped: readings with no ML residual
  // Learning phase (MonitorSettings::learning_s, learning.hpp).
  bool started = false;      // a cycle has been seen (t_start is set)
  double t_start = 0.0;      // time of the first cycle
  bool learning = false;     // still learning: no alarm
  double learning_start_s = 0.0;  // when the (latest) learning phase began
  double learning_end_s = 0.0;  // when learning ended (t_start without learning)
  int learn_count = 0;
  std::array<double, kMaxLearn> learn_z{}, learn_scratch{};
  // Each learnt sample's time, link angles and passive link force signs, for
  // the review (monitor.cpp): when learning ends, the learnt samples are
  // replayed through a copy of the filter as it stands then (`review`), one
  // window behind as the monitor tests, and what is learnt is learnt from
  // those innovations, free of the filter's settling from its prior.
  std::array<double, kMaxLearn> learn_t{};
  std::array<Eigen::Vector3d, kMaxLearn> learn_theta{}, learn_tension{};
  // The configuration map (config_map.hpp): each learnt sample's sign of the
  // joint speeds and its residual at the filter's estimate as learning ends
  // (rad). Samples are learnt from the start; the review's statistics take
  // those from learn_first on (the last three quarters).
  std::array<Eigen::Vector3d, kMaxLearn> learn_direction{};
  std::array<double, kMaxLearn> learn_r{};
  int learn_first = 0;
  bool review_map = false;  // the review's replay takes the map off its samples
  bool map_on = false;      // after learning: samples are tested less the map
  int map_cursor = 0;       // where the next look-up starts (config_map.hpp)
  int map_matched = 0;      // learnt samples (last three quarters) another pass matches
  long unmapped = 0;        // samples after learning with no learnt configuration (not tested)
  int unmapped_run = 0;     // consecutive such samples (learning starts again at `window`)
  int relearnings = 0;      // learning phases started again because the job left the map
  FilterWindow review;
  int review_stage = 0;  // 0: none; 1: residuals at the learnt estimate; 2: the lagged replay
  int review_next = 0;   // next learnt sample the review takes
  int review_kept = 0;   // samples with an innovation so far in this stage
  double review_median = 0.0;  // median of the stage-1 residuals (stated units)
  LearningSums sums;         // what the review's replay sums (reset as one when it starts)
  LearnedScale learned;      // what was learnt (defaults: nothing)
  // The step factors refined in operation (learning.hpp): each parameter's
  // batch terms so far (the review's, then one per learning_batch samples
  // that leave the window after learning with no alarm raised while they
  // were in it), the floor the review's largest terms set, and the batch
  // being summed (sum dz z, sum dz^2 per parameter, samples; a fresh one is
  // empty). step_factor[i] = max(step_floor[i], matched_factor(step_terms[i])).
  std::array<MatchedTerms, kNumParams> step_terms{};
  ParamRow step_floor = ParamRow::Ones();
  struct OperationBatch {
    ParamRow hz = ParamRow::Zero(), hh = ParamRow::Zero();
    int n = 0;
  } live;
  int operation_batches = 0;  // batches of operation the step factors took in
  double bias = 0.0;         // bias of the innovations (z units), taken off before the tests
  double t_last_accepted = 0.0;
  double chi_threshold = 0.0;  // thresholds in force (the model's, widened after learning)
  double glr_threshold = 0.0;
};

// Fresh state: estimate = model geometry, covariance = prior.
MonitorData make_monitor_data(const MonitorModel& model);

// What one cycle did.
struct StepResult {
  bool accepted = false;  // the sample entered the test and the filter
  bool alarm = false;     // an alarm was raised (data.alarms[(data.alarm_count - 1) % kMaxAlarms])
  bool explained = false; // the latest alarm's explanation was filled in (explain_samples later)
  double z = 0.0;         // normalised innovation of an accepted sample (before the bias is taken off)
  bool learnt = false;    // the learning phase (with its review) ended with this cycle
  double statistic = 0.0; // window statistic after this sample (0 while the window fills)
  double step_statistic = 0.0;  // step statistic after this sample (0 while the window fills)
};

// One servo cycle at time t_s (s, increasing) with readings theta_m (rad).
// Allocation-free.
StepResult monitor_step(const MonitorModel& model, MonitorData& data, double t_s,
                        const Eigen::Vector3d& theta_m);

// The same with the joint speeds omega (rad/s) and drive torques tau (N m) of
// the cycle, for the motion corrections of the settings. Allocation-free.
StepResult monitor_step(const MonitorModel& model, MonitorData& data, double t_s,
                        const Eigen::Vector3d& theta_m, const Eigen::Vector3d& omega,
                        const Eigen::Vector3d& tau);

// Feeds every sample still in the window to the filter (e.g. at the end of a
// run) and empties the window. Allocation-free.
void monitor_flush(const MonitorModel& model, MonitorData& data);

// Current estimate and 1-sigma (NaN for parameters not estimated).
struct Estimate {
  std::array<double, kNumParams> value{};
  std::array<double, kNumParams> sigma{};
  double growth_rate_mm_s = 0.0;  // common link growth rate (0 without a rate state)
  double growth_rate_sigma = 0.0;
};

// The filter's current estimate and 1-sigma of every parameter.
Estimate monitor_estimate(const MonitorModel& model, const MonitorData& data);

// The most recent alarm (data.alarm_count must be > 0).
const Alarm& last_alarm(const MonitorData& data);

// An alarm in words (once explained), e.g. "offset jump on joint 2 (dth2 +1.0e-04 rad) from
// 30.002 s, explains 97% of the window". Allocates: call outside the loop.
std::string describe_alarm(const Alarm& alarm);

}  // namespace gpm::calib::monitor
