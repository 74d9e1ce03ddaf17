#include "calib/monitor/monitor.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "calib/chi_square.hpp"
#include "calib/monitor/config_map.hpp"
#include "calib/monitor/drift_filter.hpp"
#include "calib/monitor/explain.hpp"
#include "calib/passive_tension.hpp"
#include "models/errors.hpp"
#include "models/kinematics.hpp"

namespace gpm::calib::monitor {
namespace {

constexpr double kDefaultLengthSigmaMm = 0.002;
constexpr double kDefaultOffsetSigmaRad = 2e-5;

void require(bool ok, const std::string& what) {
  if (!ok) throw InputError("monitor settings: " + what);
}

int slot_of(const FilterWindow& d, int j) {  // j-th oldest sample of the window
  return (d.head - d.count + j + 2 * kMaxWindow) % kMaxWindow;
}

// Window sum of z^2.
double window_statistic(const FilterWindow& d) {
  double s = 0.0;
  for (int j = 0; j < d.count; ++j) s += d.z[static_cast<size_t>(slot_of(d, j))] * d.z[static_cast<size_t>(slot_of(d, j))];
  return s;
}

// True when every joint moved at least the gate since the last accepted sample.
bool moved_enough(const MonitorModel& m, const MonitorData& d, const Eigen::Vector3d& theta_m) {
  if (!d.has_accepted) return true;
  for (int i = 0; i < 3; ++i) {
    // readings wrap at 2 pi: compare on the circle
    const double a = std::remainder(theta_m[i] - d.last_accepted[i], 2.0 * std::numbers::pi);
    if (std::abs(a) < m.motion_gate_rad) return false;
  }
  return true;
}

// Where the largest step-test term of a healthy robot over a learning phase
// lies, as a share of the threshold (for independent N(0, 1) innovations:
// the largest of ~1000 window tests over n W onsets, about 25 of 49).
constexpr double kLearnStepMaxShare = 0.5;

// Copies the filter of src (not its window) into dst.
void copy_filter(FilterWindow& dst, const FilterWindow& src) {
  static_cast<DriftFilter&>(dst) = static_cast<const DriftFilter&>(src);
}

// With the map: the monitor goes on from the review's filter (which took the
// map off the learnt samples) with an empty window (its samples carry no map).
void restart_with_map(MonitorData& d) {
  copy_filter(d, d.review);
  d.map_on = true;
  d.count = 0;
  d.statistic = 0.0;
  d.step_statistic = 0.0;
}

// Parameter i's step factor from its batch terms and floor (MonitorData::step_terms).
void set_step_factor(MonitorData& d, int i) {
  d.step_factor[i] = std::max(d.step_floor[i], matched_factor(d.step_terms[static_cast<size_t>(i)]));
}

// Ends the learning phase at t_s (learning.hpp): the learnt scale becomes the
// filter's reading noise, the learnt median the bias, the window's
// innovations are restated in the new units and the thresholds widen.
void finish_learning(const MonitorModel& m, MonitorData& d, double t_s) {
  d.learning = false;
  d.learning_end_s = t_s;
  const int n = d.review_kept;  // the replayed innovations in learn_z
  // With the map a tested residual is the difference of two readings' (the
  // sample's and the map's, each with the stated error): its stated scale is
  // sqrt(2) that of one.
  const double floor = m.settings.scale_floor * (d.review_map ? std::numbers::sqrt2 : 1.0);
  d.learned = learn_innovation_scale(d.learn_z.data(), n, m.settings.learning_batch, floor, d.learn_scratch.data());
  const double s = d.learned.scale;
  if (d.review_map) restart_with_map(d);
  d.noise_scale = s;
  d.bias = d.learned.median / s;
  for (int j = 0; j < d.count; ++j) {
    const auto slot = static_cast<size_t>(slot_of(d, j));
    d.z[slot] = (d.z[slot] - d.learned.median) / s;
    d.dz[slot] /= s;
    d.z_filter[slot] /= s;
  }
  // The step test: each parameter's statistic divided by its own factor
  // (the reported step_factor is the largest); the threshold stays.
  const int batches = n / m.settings.learning_batch;
  double largest = 1.0;
  for (int k = 0; k < m.n_free; ++k) {
    const int i = m.free_index[static_cast<size_t>(k)];
    d.step_terms[static_cast<size_t>(i)] = matched_terms(batches, d.learned.median, s, [&](int b) {
      const auto u = static_cast<size_t>(b);
      return MatchedBatch{d.sums.h[u][i], d.sums.hz[u][i], d.sums.hh[u][i]};
    });
    // The largest term seen while learning, in the new units, sits where a
    // healthy robot's would: a structured reading error repeats with the job
    // (not Gaussian), and the batches see it only on average.
    d.step_floor[i] = std::max(1.0, d.sums.step_max[i] / (s * s) / (kLearnStepMaxShare * m.glr_threshold));
    set_step_factor(d, i);
    largest = std::max(largest, d.step_factor[i]);
  }
  d.live = {};
  d.learned.step_factor = largest;
  d.learned.map = d.map_on;
  d.learned.map_matched = d.map_matched;
  d.glr_threshold = m.glr_threshold;
  const double W = m.settings.window;
  const double kappa = d.learned.chi_factor, nu = W * d.learned.chi_mean / kappa;
  d.chi_threshold = std::max(m.threshold, kappa * chi2_quantile_wilson_hilferty(nu, m.chi_normal_quantile));
  // As for the step test: the largest window sum seen while learning sits
  // where a healthy robot's would, W + 3 sqrt(2 W).
  d.chi_threshold = std::max(d.chi_threshold, d.sums.chi_max / (s * s) * m.threshold / (W + 3.0 * std::sqrt(2.0 * W)));
}

// Review of the learning phase (MonitorData::review): how many learnt
// samples a cycle that accepted no live sample takes, in each stage, at a
// servo rate of kReviewRateHz or above (each such cycle stays well within the
// cost of an accepted cycle).
constexpr int kReviewResidualsPerCycle = 4;
constexpr int kReviewReplayPerCycle = 1;
constexpr double kReviewRateHz = 4000.0;

// The review's work in a cycle, in units of the above: one on a cycle that
// accepted no live sample (at most what an accepted sample costs); at a
// slower servo rate a cycle is longer and takes proportionally more (the same
// share of the cycle as at kReviewRateHz), less the unit an accepted sample
// took, so that the review lasts about as long in time whatever the rate (a
// 250 Hz drive bus, where nearly every cycle accepts a sample: 16 units a
// free cycle, 15 an accepted one).
int review_units(const MonitorModel& m, bool accepted) {
  const int units = std::max(1, static_cast<int>(std::ceil(kReviewRateHz / m.settings.cycle_hz - 1e-9)));
  return accepted ? units - 1 : units;
}

// Starts the review of the learnt samples with a copy of the filter as
// learning ends: first their residuals at its estimate (stage 1).
void begin_review(MonitorData& d) {
  copy_filter(d.review, d);
  d.review.count = 0;
  d.review.head = 0;
  d.review_stage = 1;
  d.review_next = 0;
  d.review_kept = 0;
}

// The map holds the residuals at the estimate as learning ends: the filter
// that takes it off goes on from there with no growth rate (what the rate
// estimated while learning, from readings it did not yet know the robot's
// error of, is in the map), its rate back at its prior.
void restart_rate(const MonitorModel& m, DriftFilter& f) {
  const int rho = m.rate_index;
  f.growth_rate = 0.0;
  f.P.row(rho).setZero();
  f.P.col(rho).setZero();
  f.P(rho, rho) = m.prior_variance[static_cast<size_t>(rho)];
}

// Stage 2 from the stage-1 residuals: the robot's own scale about the learnt
// estimate becomes the replay filter's reading noise, and the replay starts
// from the first reviewed sample's time with empty sums, taking the map off
// its samples when with_map.
void start_replay(const MonitorModel& m, MonitorData& d, bool with_map) {
  const LearnedScale at = learn_innovation_scale(d.learn_z.data(), d.review_kept, m.settings.learning_batch,
                                                 m.settings.scale_floor, d.learn_scratch.data());
  d.review_median = at.median;
  d.review.noise_scale = at.scale;
  d.review.t_last_update = d.learn_t[static_cast<size_t>(d.learn_first)];
  d.review.count = 0;
  d.review.head = 0;
  d.sums = LearningSums{};
  d.review_stage = 2;
  d.review_next = d.learn_first;
  d.review_kept = 0;
  d.review_map = with_map;
  d.map_cursor = 0;
  if (with_map && m.rate_index >= 0) restart_rate(m, d.review);
}

// Leave-one-out half-width of the review's map look-ups (s): a learnt sample
// is matched by the learnt samples of other passes only.
constexpr double kMapExcludeS = 0.5;

// The learnt samples as a map: those of the last three quarters (in the
// first, the robot's motion settles from its start: on the twins its
// residual then differs from the later passes' by a few sigma).
MapSamples map_samples(const MonitorData& d) {
  const auto f = static_cast<size_t>(d.learn_first);
  return {d.learn_t.data() + f, d.learn_theta.data() + f, d.learn_direction.data() + f, d.learn_r.data() + f,
          d.learn_count - d.learn_first};
}

// The map's residual at link angles theta moving in `direction`, excluding the
// learnt samples within exclude_halfwidth_s of exclude_t; false with none.
bool map_at(const MonitorModel& m, MonitorData& d, const Eigen::Vector3d& theta, const Eigen::Vector3d& direction,
            double exclude_t, double exclude_halfwidth_s, double& r_map) {
  const MapQuery q{theta, direction, m.settings.map_radius_rad, m.settings.map_pass_gap_s, exclude_t,
                   exclude_halfwidth_s};
  return map_residual(map_samples(d), q, d.map_cursor, r_map);
}

// Stage 2, one learnt sample: the replay filter tests it one window behind,
// as the monitor will, and its innovation (in the stated units) and the
// window's largest statistics (last three quarters) are what the learning
// phase learns from.
void replay_sample(const MonitorModel& m, MonitorData& d, int j) {
  FilterWindow& r = d.review;
  const int W = m.settings.window;
  const auto u = static_cast<size_t>(j);
  double r_map = 0.0;
  if (d.review_map && !map_at(m, d, d.learn_theta[u], d.learn_direction[u], d.learn_t[u], kMapExcludeS, r_map)) return;
  if (r.count >= W) {
    const auto oldest = static_cast<size_t>(slot_of(r, 0));
    filter_update(m, r, r.t[oldest], r.theta[oldest], r.tension[oldest], r.r_map[oldest]);
    --r.count;
  }
  double z = 0.0, z_filter = 0.0;
  ParamRow dz;
  if (!filter_innovation(m, r, d.learn_t[u], d.learn_theta[u], d.learn_tension[u], z, dz, r_map, nullptr, &z_filter))
    return;
  const double s0 = r.noise_scale;
  const double median = d.review_map ? 0.0 : d.review_median;  // (the map takes off the level too)
  const auto slot = static_cast<size_t>(r.head);
  r.r_map[slot] = r_map;
  r.z[slot] = z - median / s0;
  r.dz[slot] = dz;
  r.z_filter[slot] = z_filter;
  r.t[slot] = d.learn_t[u];
  r.theta[slot] = d.learn_theta[u];
  r.tension[slot] = d.learn_tension[u];
  r.head = (r.head + 1) % kMaxWindow;
  ++r.count;
  const double z1 = z * s0;
  const ParamRow dz1 = dz * s0;
  const auto b = static_cast<size_t>(d.review_kept / m.settings.learning_batch);
  d.sums.h[b] += dz1;
  d.sums.hz[b] += z1 * dz1;
  d.sums.hh[b] += dz1.cwiseProduct(dz1);
  d.learn_z[static_cast<size_t>(d.review_kept++)] = z1;
  if (r.count == W && 4 * (j - d.learn_first) >= d.learn_count - d.learn_first) {
    ParamRow largest = ParamRow::Zero();
    step_statistic(m, r, &largest);
    d.sums.step_max = d.sums.step_max.cwiseMax(largest * (s0 * s0));
    d.sums.chi_max = std::max(d.sums.chi_max, window_statistic(r) * s0 * s0);
  }
}

// One cycle's share of the review (`units` of work, review_units); true when
// it ended the learning phase at t_s.
bool review_step(const MonitorModel& m, MonitorData& d, double t_s, int units) {
  if (d.review_stage == 1) {
    for (int c = 0; c < units * kReviewResidualsPerCycle && d.review_next < d.learn_count; ++c) {
      const int j = d.review_next++;
      const auto u = static_cast<size_t>(j);
      double z = 0.0, r = 0.0;
      ParamRow dz;
      const bool ok = filter_innovation(m, d.review, d.review.t_last_update, d.learn_theta[u], d.learn_tension[u], z,
                                        dz, 0.0, &r);
      d.learn_r[u] = ok ? r : 0.0;
      if (!ok) d.learn_direction[u].setConstant(2.0);  // (no sign: never matched)
      if (ok && j >= d.learn_first) d.learn_z[static_cast<size_t>(d.review_kept++)] = z;
      // How many learnt samples another pass matches (the map's coverage:
      // configurations and directions are known before the residuals).
      double unused = 0.0;
      if (ok && j >= d.learn_first && m.settings.map_radius_rad > 0.0 &&
          map_at(m, d, d.learn_theta[u], d.learn_direction[u], d.learn_t[u], kMapExcludeS, unused))
        ++d.map_matched;
    }
    if (d.review_next >= d.learn_count) start_replay(m, d, d.map_matched >= 4 * m.settings.learning_batch);
    return false;
  }
  // The learning phase ends on a cycle of its own (its cost: BM_MonitorStepLearningEnd).
  if (d.review_next < d.learn_count) {
    for (int c = 0; c < units * kReviewReplayPerCycle && d.review_next < d.learn_count; ++c)
      replay_sample(m, d, d.review_next++);
    return false;
  }
  d.review_stage = 0;
  finish_learning(m, d, t_s);
  return true;
}

}  // namespace

std::array<double, kNumParams> MonitorSettings::nan_array() {
  std::array<double, kNumParams> a;
  a.fill(std::numeric_limits<double>::quiet_NaN());
  return a;
}

namespace {

// Throws InputError naming the first setting of s out of its range.
void check_settings(const MonitorSettings& s) {
  check_reading_model(s.reading, "monitor settings: ");
  require(s.cycle_hz > 0.0 && std::isfinite(s.cycle_hz), "cycle_hz must be > 0");
  require(s.decimation >= 1, "decimation must be >= 1");
  require(s.window >= 2 && s.window <= kMaxWindow / 2,
          fmt::format("window {} must be in 2..{}", s.window, kMaxWindow / 2));
  require(s.step_min_samples >= 1 && s.step_min_samples <= s.window,
          fmt::format("step_min_samples {} must be in 1..{} (window)", s.step_min_samples, s.window));
  require(s.step_clip >= 0.0 && !std::isnan(s.step_clip), "step_clip must be >= 0 (0: no clipping)");
  require(s.explain_samples >= 1 && s.explain_samples <= kMaxWindow - s.window,
          fmt::format("explain_samples {} must be in 1..{} (kMaxWindow - window)", s.explain_samples,
                      kMaxWindow - s.window));
  require(s.false_alarms_per_hour > 0.0 && std::isfinite(s.false_alarms_per_hour),
          "false_alarms_per_hour must be > 0");
  require(s.thermal_tau_s > 0.0, "thermal_tau_s must be > 0 (inf: no drift)");
  require(s.thermal_growth_mm >= 0.0 && s.length_drift_mm >= 0.0 && s.offset_drift_rad >= 0.0,
          "drift scales must be >= 0");
  require(s.jump_offset_rad > 0.0 && s.jump_length_mm > 0.0, "jump scales must be > 0");
  require(s.min_motion_counts >= 0.0, "min_motion_counts must be >= 0");
  require(s.estimate.any(), "no parameter to estimate");
  require(s.friction_stick_rad_s >= 0.0 && std::isfinite(s.friction_stick_rad_s), "friction_stick_rad_s must be >= 0");
  require(s.tension_min_N >= 0.0 && std::isfinite(s.tension_min_N), "tension_min_N must be >= 0");
  require(s.learning_s >= 0.0 && s.learning_s <= 10.0, fmt::format("learning_s {} must be in 0..10 s", s.learning_s));
  require(s.learning_batch >= kMaxLearn / kMaxLearnBatches && s.learning_batch <= kMaxLearn / 4,
          fmt::format("learning_batch {} must be in {}..{}", s.learning_batch, kMaxLearn / kMaxLearnBatches,
                      kMaxLearn / 4));
  require(s.bias_tau_s > 0.0, "bias_tau_s must be > 0");
  require(s.scale_floor >= 1.0 && std::isfinite(s.scale_floor), "scale_floor must be finite and >= 1");
  require(s.map_radius_rad >= 0.0 && std::isfinite(s.map_radius_rad), "map_radius_rad must be finite and >= 0");
  require(s.map_pass_gap_s > 0.0 && std::isfinite(s.map_pass_gap_s), "map_pass_gap_s must be finite and > 0");
}

// The test's noise, gate and thresholds of m from its settings.
void set_change_test(MonitorModel& m) {
  const MonitorSettings& s = m.settings;
  const double count = encoder_step_rad(s.reading.encoder_bits);
  m.sigma_rad = reading_sigma(s.reading);
  m.motion_gate_rad = s.min_motion_counts * (count > 0.0 ? count : s.reading.noise_rad);
  m.tests_per_hour = 3600.0 * s.cycle_hz / s.decimation;
  m.p_window = s.false_alarms_per_hour / m.tests_per_hour;
  require(m.p_window < 0.5, "false_alarms_per_hour is larger than the number of tests per hour");
  m.threshold = chi2_upper_quantile(s.window, 0.5 * m.p_window);
}

// The coordinates of the estimated parameters (scale, growth, drift, prior);
// true when a length or base coordinate is among them.
bool add_parameter_states(MonitorModel& m, double mean_la, double mean_l, double per_tau) {
  const MonitorSettings& s = m.settings;
  bool any_length = false;
  for (int i = 0; i < kNumParams; ++i) {
    if (!s.estimate.test(static_cast<size_t>(i))) continue;
    const auto k = static_cast<size_t>(m.n_free++);
    m.free_index[k] = i;
    m.scale[k] = is_offset(i) ? mean_la : 1.0;
    const double prior = std::isnan(s.prior_sigma[static_cast<size_t>(i)])
                             ? (is_offset(i) ? kDefaultOffsetSigmaRad : kDefaultLengthSigmaMm)
                             : s.prior_sigma[static_cast<size_t>(i)];
    require(prior > 0.0 && std::isfinite(prior), fmt::format("prior_sigma of {} must be > 0", param_name(i)));
    const double drift = m.scale[k] * (is_offset(i) ? s.offset_drift_rad : s.length_drift_mm);
    m.growth[k] = is_length(i) ? s.geometry[i] / mean_l : 0.0;
    any_length = any_length || is_length(i);
    // Independent random walks whose spread over one time constant is the drift scale.
    m.drift_rate[k] = drift * drift * per_tau;
    m.prior_variance[k] = std::pow(m.scale[k] * prior, 2);
    m.variance_cap[k] = m.prior_variance[k] + drift * drift + std::pow(m.growth[k] * s.thermal_growth_mm, 2);
  }
  return any_length;
}

// The common growth rate's coordinate: of order A / tau, changing by A / tau
// over tau (a random walk of variance (A / tau)^2 per tau).
void add_rate_state(MonitorModel& m, double per_tau) {
  m.rate_index = m.n_state++;
  const double rate = m.settings.thermal_growth_mm * per_tau;
  m.rate_noise = rate * rate * per_tau;
  m.prior_variance[static_cast<size_t>(m.rate_index)] = rate * rate;
  m.variance_cap[static_cast<size_t>(m.rate_index)] = 4.0 * rate * rate;
}

// The cyclic error's coordinates a_i, b_i = A_i cos(phase_i), A_i sin(phase_i)
// with a uniform phase: variance A_i^2 / 2 each; constant (no process noise).
void add_cyclic_states(MonitorModel& m, double mean_la) {
  m.cyclic_index = m.n_state;
  for (int c = 0; c < kNumCyclic; ++c) {
    const auto k = static_cast<size_t>(m.n_state++);
    const double a = m.settings.reading.cyclic_rad[static_cast<size_t>(c / 2)];
    m.scale[k] = mean_la;
    m.prior_variance[k] = std::max(mean_la * mean_la * a * a / 2.0, 1e-30);
    m.variance_cap[k] = m.prior_variance[k];
  }
}

// The passive links' effective play d_i: with learning the stated play is a
// bound, not a value (a robot better than its data sheet has less): mean
// d / 2 (make_monitor_data), 1-sigma d / 2; without, 1-sigma d / 4.
void add_clearance_states(MonitorModel& m) {
  m.clearance_index = m.n_state;
  for (int i = 0; i < 3; ++i) {
    const auto k = static_cast<size_t>(m.n_state++);
    const double c = m.settings.reading.clearance_mm[static_cast<size_t>(i)];
    m.scale[k] = 1.0;
    m.prior_variance[k] = std::max((m.settings.learning_s > 0.0 ? 0.25 : 0.0625) * c * c, 1e-30);
    m.variance_cap[k] = m.prior_variance[k];
  }
}

bool any_positive(const std::array<double, 3>& v) { return v[0] > 0.0 || v[1] > 0.0 || v[2] > 0.0; }

}  // namespace

MonitorModel make_monitor_model(const MonitorSettings& s) {
  check_settings(s);
  MonitorModel m;
  m.settings = s;
  set_change_test(m);
  const double mean_la = (s.geometry.la_(0) + s.geometry.la_(1) + s.geometry.la_(2)) / 3.0;
  const double mean_l = (mean_la + (s.geometry.lb_(0) + s.geometry.lb_(1) + s.geometry.lb_(2)) / 3.0) / 2.0;
  const double per_tau = std::isfinite(s.thermal_tau_s) ? 1.0 / s.thermal_tau_s : 0.0;
  const bool any_length = add_parameter_states(m, mean_la, mean_l, per_tau);
  m.n_state = m.n_free;
  if (any_length && s.thermal_growth_mm > 0.0 && per_tau > 0.0) add_rate_state(m, per_tau);
  if (any_positive(s.reading.cyclic_rad)) add_cyclic_states(m, mean_la);
  m.has_clearance = any_positive(s.reading.clearance_mm);
  if (m.has_clearance) add_clearance_states(m);
  m.glr_threshold = chi2_upper_quantile(1, 0.5 * m.p_window / (m.n_free * s.window));
  m.chi_normal_quantile = wilson_hilferty_normal_quantile(s.window, m.threshold);
  return m;
}

MonitorData make_monitor_data(const MonitorModel& m) {
  MonitorData d;
  d.estimate = m.settings.geometry;
  d.clearance = m.settings.reading.clearance_mm;
  if (m.settings.learning_s > 0.0)
    for (double& c : d.clearance) c *= 0.5;
  d.learning = m.settings.learning_s > 0.0;
  d.chi_threshold = m.threshold;
  d.glr_threshold = m.glr_threshold;
  d.P.setZero();
  for (int k = 0; k < m.n_state; ++k) d.P(k, k) = m.prior_variance[static_cast<size_t>(k)];
  return d;
}

void monitor_flush(const MonitorModel& m, MonitorData& d) {
  for (int j = 0; j < d.count; ++j) {
    const auto slot = static_cast<size_t>(slot_of(d, j));
    filter_update(m, d, d.t[slot], d.theta[slot], d.tension[slot], d.r_map[slot]);
  }
  d.count = 0;
  d.statistic = 0.0;
  d.step_statistic = 0.0;
}

StepResult monitor_step(const MonitorModel& m, MonitorData& d, double t_s, const Eigen::Vector3d& theta_m) {
  return monitor_step(m, d, t_s, theta_m, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
}

namespace {

// A reading corrected by the reading model (calib/reading_model.hpp): the link
// angles, the torques the transmissions carry and the flank of each mesh.
struct LinkReading {
  Eigen::Vector3d theta, carried, flank;
};

// The link angles readings theta_raw stand for at joint speeds omega and drive
// torques tau (no acceleration given: no inertia term).
LinkReading link_reading(const MonitorModel& m, const Eigen::Vector3d& theta_raw, const Eigen::Vector3d& omega,
                         const Eigen::Vector3d& tau) {
  const ReadingModel& reading = m.settings.reading;
  LinkReading l;
  for (int i = 0; i < 3; ++i) {
    l.carried[i] = transmitted_torque(reading.load, i, tau[i], omega[i], 0.0);
    l.flank[i] = std::abs(l.carried[i]) >= kFlankTorqueMinNm ? (l.carried[i] > 0.0 ? 1.0 : -1.0) : 0.0;
    l.theta[i] = link_angle(reading, i, theta_raw[i], omega[i], l.carried[i], l.flank[i]);
  }
  return l;
}

// True when the reading model cannot tell some joint's link angle: the
// friction's twist while the joint sticks, or a mesh crossing its backlash.
bool uncertain_reading(const MonitorModel& m, const Eigen::Vector3d& omega, const LinkReading& l) {
  const ReadingModel& reading = m.settings.reading;
  for (int i = 0; i < 3; ++i) {
    const auto k = static_cast<size_t>(i);
    if (reading.compliance_rad_per_Nm[k] * reading.load.coulomb_Nm[k] > 0.5 * m.sigma_rad &&
        std::abs(omega[i]) < m.settings.friction_stick_rad_s)
      return true;
    if (reading.backlash_rad[k] > 0.0 && l.flank[i] == 0.0) return true;
  }
  return false;
}

// Clearance (ReadingModel::clearance_mm): each passive link acts as
// lb_i + d_i sign(T_i), T_i its axial force from the moment balance of the
// active link. The sign of each link's force (0 without a play); nullopt when
// some sign is uncertain or the pose has no forward kinematics (counted as skipped).
std::optional<Eigen::Vector3d> tension_signs(const MonitorModel& m, MonitorData& d, const LinkReading& l) {
  Eigen::Vector3d sign = Eigen::Vector3d::Zero();
  if (!m.has_clearance) return sign;
  Eigen::Vector3d theta_a;
  for (int i = 0; i < 3; ++i) theta_a[i] = l.theta[i] + d.estimate.dth_(i);
  const std::optional<ForwardResult> fk = forward_kinematics(d.estimate, theta_a);
  if (!fk) {
    ++d.skipped;
    return std::nullopt;
  }
  for (int i = 0; i < 3; ++i) {
    if (m.settings.reading.clearance_mm[static_cast<size_t>(i)] <= 0.0) continue;
    const double tension = passive_link_tension(d.estimate, i, theta_a[i], fk->theta_b[i], l.carried[i]);
    if (!(std::abs(tension) >= m.settings.tension_min_N)) return std::nullopt;
    sign[i] = tension > 0.0 ? 1.0 : -1.0;
  }
  return sign;
}

// The accepted innovation z at t_s: its sample (time, link angles theta,
// force signs, direction of motion) kept while learning for the review and
// the map (the review's statistics leave out the first quarter, where the
// filter settles on what the calibration left), then z
// followed as a slowly varying bias; returns z less the bias before this
// sample.
double learn_and_debias(const MonitorModel& m, MonitorData& d, double t_s, double z, const Eigen::Vector3d& theta,
                        const Eigen::Vector3d& tension, const Eigen::Vector3d& direction) {
  if (d.learning && d.review_stage == 0 && d.learn_count < kMaxLearn) {
    if (t_s - d.learning_start_s < 0.25 * m.settings.learning_s) d.learn_first = d.learn_count + 1;
    const auto j = static_cast<size_t>(d.learn_count++);
    d.learn_t[j] = t_s;
    d.learn_theta[j] = theta;
    d.learn_tension[j] = tension;
    d.learn_direction[j] = direction;
  }
  const double z_tested = z - d.bias;
  if (!d.learning && m.settings.learning_s > 0.0 && d.pending < 0 && d.accepted > 1)
    d.bias += (z - d.bias) * std::min(1.0, (t_s - d.t_last_accepted) / m.settings.bias_tau_s);
  d.t_last_accepted = t_s;
  return z_tested;
}

// Explains the pending alarm with the samples after its crossing (over a
// short arc the sensitivity columns are nearly collinear), then re-baselines:
// applies the explained change and opens its variance to its size, so the
// filter absorbs any remainder; the window (innovations against the old
// estimate) is dropped and refilled.
void explain_pending(const MonitorModel& m, MonitorData& d, double t_s) {
  Alarm& a = d.alarms[static_cast<size_t>((d.alarm_count - 1) % kMaxAlarms)];
  explain_window(m, d, a);
  a.explained_s = t_s;
  d.estimate[a.param] += a.delta;
  for (int k = 0; k < m.n_free; ++k)
    if (m.free_index[static_cast<size_t>(k)] == a.param) {
      const double v = std::pow(a.delta * m.scale[static_cast<size_t>(k)], 2);
      if (v > d.P(k, k)) d.P(k, k) = v;
    }
  d.count = 0;
  d.statistic = 0.0;
  d.step_statistic = 0.0;
  d.pending = -1;
}

// Records an alarm at t_s by the test further past its threshold, to be
// explained explain_samples later.
void raise_alarm(const MonitorModel& m, MonitorData& d, double t_s) {
  Alarm& a = d.alarms[static_cast<size_t>(d.alarm_count % kMaxAlarms)];
  a = Alarm{};
  a.t_s = t_s;
  const bool step = d.step_statistic / d.glr_threshold > d.statistic / d.chi_threshold;
  a.kind = step ? AlarmKind::kStep : AlarmKind::kChiSquare;
  a.statistic = step ? d.step_statistic : d.statistic;
  a.threshold = step ? d.glr_threshold : d.chi_threshold;
  ++d.alarm_count;
  d.pending = std::max(m.settings.explain_samples, 1);
}

// The job has left the learnt configurations (a window of consecutive
// samples off the map): a pending alarm is explained with what the window
// holds, the window's samples go to the filter, and learning starts again at
// t_s from the filter as it stands, with the stated reading model and tests
// until its review ends (no alarm meanwhile).
void start_relearning(const MonitorModel& m, MonitorData& d, double t_s) {
  if (d.pending > 0) explain_pending(m, d, t_s);
  monitor_flush(m, d);
  d.learning = true;
  d.learning_start_s = t_s;
  d.learn_count = 0;
  d.learn_first = 0;
  d.map_on = false;
  d.map_matched = 0;
  d.map_cursor = 0;
  d.noise_scale = 1.0;
  d.bias = 0.0;
  d.step_factor = ParamRow::Ones();
  d.chi_threshold = m.threshold;
  d.glr_threshold = m.glr_threshold;
  d.unmapped_run = 0;
  ++d.relearnings;
}

// A tested sample leaves the window into the filter: after learning, its
// terms join the step factors' batch in the making (learning.hpp; z and dz in
// the learnt units, the bias taken off, as the review's replay summed them),
// unless an alarm was raised while it was in the window; each full batch
// refines every step factor, which narrows as the batches add up (the
// review's 6 s give about ten: their widening is a factor 1.5) or widens
// where the robot errs more than it did while learning.
void refine_step_factors(const MonitorModel& m, MonitorData& d, int slot) {
  if (!m.settings.refine_step_factors || m.settings.learning_s <= 0.0 || d.learning || d.review_stage > 0) return;
  const auto u = static_cast<size_t>(slot);
  if (d.alarm_count > 0 && d.t[u] <= d.alarms[static_cast<size_t>((d.alarm_count - 1) % kMaxAlarms)].explained_s) return;
  d.live.hz += d.dz[u] * d.z[u];
  d.live.hh += d.dz[u].cwiseProduct(d.dz[u]);
  if (++d.live.n < m.settings.learning_batch) return;
  for (int k = 0; k < m.n_free; ++k) {
    const int i = m.free_index[static_cast<size_t>(k)];
    MatchedTerms& t = d.step_terms[static_cast<size_t>(i)];
    if (d.live.hh[i] > 0.0) {
      t.sum += d.live.hz[i] * d.live.hz[i] / d.live.hh[i];
      ++t.count;
    }
    set_step_factor(d, i);
  }
  d.live = {};
  ++d.operation_batches;
}

// Appends a tested sample to the window.
void store_sample(MonitorData& d, double t_s, double z_tested, const ParamRow& dz, double z_filter,
                  const Eigen::Vector3d& theta, const Eigen::Vector3d& tension_sign, double r_map) {
  const auto slot = static_cast<size_t>(d.head);
  d.z_filter[slot] = z_filter;
  d.r_map[slot] = r_map;
  d.z[slot] = z_tested;
  d.t[slot] = t_s;
  d.dz[slot] = dz;
  d.theta[slot] = theta;
  d.tension[slot] = tension_sign;
  d.head = (d.head + 1) % kMaxWindow;
  ++d.count;
}

// The map's key: the signs that switch the reading error under the reading
// model: each joint's speed, each passive link's force (0 without a
// clearance) and each mesh flank of a joint with backlash (without backlash
// the flank changes nothing: a drive whose torque crosses zero stays on the
// learnt map).
Eigen::Vector3d map_key(const MonitorModel& m, const Eigen::Vector3d& omega, const Eigen::Vector3d& tension_sign,
                        const LinkReading& l) {
  Eigen::Vector3d key = omega.cwiseSign() + 3.0 * tension_sign;
  for (int i = 0; i < 3; ++i)
    if (m.settings.reading.backlash_rad[static_cast<size_t>(i)] > 0.0) key[i] += 9.0 * l.flank[i];
  return key;
}

// Counts a servo cycle at t_s; the first starts the clock.
void count_cycle(MonitorData& d, double t_s) {
  ++d.cycles;
  ++d.cycles_since_accepted;
  if (d.started) return;
  d.started = true;
  d.t_start = t_s;
  d.learning_start_s = t_s;
  if (!d.learning) d.learning_end_s = t_s;
}

}  // namespace

namespace {

// One cycle's work on the live readings (monitor_step without the review).
StepResult step_live(const MonitorModel& m, MonitorData& d, double t_s, const Eigen::Vector3d& theta_raw,
                     const Eigen::Vector3d& omega, const Eigen::Vector3d& tau) {
  StepResult out;
  const LinkReading l = link_reading(m, theta_raw, omega, tau);
  count_cycle(d, t_s);
  // Independence gate (README.md): at most one sample per `decimation`
  // cycles, and only when every joint has moved, so that the quantisation
  // errors of accepted samples are not copies of each other. The first
  // reading is only the reference of the motion gate: a robot starting from
  // rest gives no sample until every joint moves.
  if (!d.has_accepted) {
    d.has_accepted = true;
    d.last_accepted = theta_raw;
    d.cycles_since_accepted = 0;
    return out;
  }
  if (d.cycles_since_accepted < m.settings.decimation || !moved_enough(m, d, theta_raw) ||
      uncertain_reading(m, omega, l))
    return out;
  // The oldest sample leaves a full window and updates the filter; while an
  // alarm waits for its explanation the filter waits too (it must not absorb
  // the change before it is explained).
  const int W = m.settings.window;
  if (d.count >= W && d.pending < 0) {
    const auto oldest = static_cast<size_t>(slot_of(d, 0));
    refine_step_factors(m, d, static_cast<int>(oldest));
    filter_update(m, d, d.t[oldest], d.theta[oldest], d.tension[oldest], d.r_map[oldest]);
    --d.count;
  }
  const std::optional<Eigen::Vector3d> tension_sign = tension_signs(m, d, l);
  if (!tension_sign) return out;
  const Eigen::Vector3d direction = map_key(m, omega, *tension_sign, l);
  double r_map = 0.0;
  if (d.map_on && !map_at(m, d, l.theta, direction, 0.0, -1.0, r_map)) {
    ++d.unmapped;
    if (++d.unmapped_run >= W) start_relearning(m, d, t_s);
    return out;
  }
  d.unmapped_run = 0;
  // Innovation against the filter (which has seen no sample of the window) predicted to t_s.
  double z = 0.0, z_filter = 0.0;
  ParamRow dz;
  if (!filter_innovation(m, d, t_s, l.theta, *tension_sign, z, dz, r_map, nullptr, &z_filter)) {
    ++d.skipped;
    return out;
  }
  d.has_accepted = true;
  d.last_accepted = theta_raw;
  d.cycles_since_accepted = 0;
  ++d.accepted;
  store_sample(d, t_s, learn_and_debias(m, d, t_s, z, l.theta, *tension_sign, direction), dz, z_filter, l.theta,
               *tension_sign, r_map);
  if (d.learning && d.review_stage == 0 && (t_s - d.learning_start_s >= m.settings.learning_s || d.learn_count >= kMaxLearn))
    begin_review(d);
  const bool full = d.count == W && d.pending < 0;
  d.statistic = full ? window_statistic(d) : 0.0;
  d.step_statistic = full ? step_statistic(m, d) : 0.0;
  d.last_z = z;
  out.accepted = true;
  out.z = z;
  out.statistic = d.statistic;
  out.step_statistic = d.step_statistic;
  if (d.pending > 0 && --d.pending == 0) {
    explain_pending(m, d, t_s);
    out.explained = true;
  } else if (d.pending < 0 && !d.learning && d.filtered >= W &&
             (d.statistic > d.chi_threshold || d.step_statistic > d.glr_threshold)) {
    // (No alarm before the filter has absorbed one window: until then the
    // innovations share the prior's error of the nuisance states, cyclic
    // error and clearance, which the step test does not normalise by.)
    raise_alarm(m, d, t_s);
    out.alarm = true;
  }
  return out;
}

}  // namespace

StepResult monitor_step(const MonitorModel& m, MonitorData& d, double t_s, const Eigen::Vector3d& theta_raw,
                        const Eigen::Vector3d& omega, const Eigen::Vector3d& tau) {
  StepResult out = step_live(m, d, t_s, theta_raw, omega, tau);
  // The review of the learning phase runs on cycles without a live sample
  // (and beside one where the servo rate leaves time: review_units).
  if (d.review_stage > 0) {
    const int units = review_units(m, out.accepted);
    if (units > 0) out.learnt = review_step(m, d, t_s, units);
  }
  return out;
}

Estimate monitor_estimate(const MonitorModel& m, const MonitorData& d) {
  Estimate e;
  e.value = d.estimate.values;
  e.sigma.fill(std::numeric_limits<double>::quiet_NaN());
  for (int k = 0; k < m.n_free; ++k)
    e.sigma[static_cast<size_t>(m.free_index[static_cast<size_t>(k)])] =
        std::sqrt(d.P(k, k)) / m.scale[static_cast<size_t>(k)];
  if (m.rate_index >= 0) {
    e.growth_rate_mm_s = d.growth_rate;
    e.growth_rate_sigma = std::sqrt(d.P(m.rate_index, m.rate_index));
  }
  return e;
}

const char* alarm_kind_name(AlarmKind kind) { return kind == AlarmKind::kStep ? "step" : "chi_square"; }

const Alarm& last_alarm(const MonitorData& d) {
  return d.alarms[static_cast<size_t>((d.alarm_count - 1) % kMaxAlarms)];
}

std::string describe_alarm(const Alarm& a) {
  std::string what;
  const auto name = param_name(a.param);
  if (is_offset(a.param)) {
    what = fmt::format("offset jump on joint {} ({} {:+.1e} rad)", a.param - kDth1 + 1, name, a.delta);
  } else if (is_length(a.param)) {
    what = fmt::format("link {} ({} {:+.1e} mm)", a.delta >= 0.0 ? "growth" : "shrinkage", name, a.delta);
  } else {
    what = fmt::format("base joint shift ({} {:+.1e} mm)", name, a.delta);
  }
  return fmt::format("{} from {:.3f} s, explains {:.0f}% of the window", what, a.onset_s, 100.0 * a.explained);
}

}  // namespace gpm::calib::monitor
