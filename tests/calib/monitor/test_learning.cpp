// Tests of calib/monitor/learning.cpp (the learning phase's estimates against
// closed forms) and of the learning phase in calib/monitor/monitor.cpp on
// generated readings (circle_stream.hpp): no alarm while learning, the learnt
// scale of a robot noisier than stated, and a slip after learning still found
// within 1 s and named.
#include "calib/monitor/learning.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "calib/chi_square.hpp"
#include "calib/monitor/monitor.hpp"
#include "models/rng.hpp"
#include "tests/calib/monitor/run_circle.hpp"

namespace gpm::calib::monitor {
namespace {

using testing::run_circle;

LearnedScale learn(const std::vector<double>& z, int batch, double floor = 1.0) {
  std::vector<double> scratch(z.size());
  return learn_innovation_scale(z.data(), static_cast<int>(z.size()), batch, floor, scratch.data());
}

// Independent N(bias, s^2): the median is the bias, 1.4826 MAD the scale; the
// scale used is the MAD's upper bound 1.4826 MAD (1 + 2.2 / sqrt(n)).
TEST(Learning, ScaleAndBiasOfIndependentInnovations) {
  Rng rng(7);
  std::vector<double> z(2000);
  for (double& v : z) v = 0.5 + 3.0 * rng.normal();
  const LearnedScale l = learn(z, 50);
  EXPECT_EQ(l.samples, 2000);
  EXPECT_NEAR(l.median, 0.5, 0.15);
  EXPECT_NEAR(l.mad_scale, 3.0, 0.15);
  EXPECT_NEAR(l.scale, l.mad_scale * (1.0 + 2.2 / std::sqrt(l.effective_samples)), 1e-9);
  EXPECT_GT(l.effective_samples, 1000.0);  // independent: about n
  // Independent samples: the factors are 1 up to their widening (one standard error).
  EXPECT_GE(l.step_factor, 1.0);
  EXPECT_LT(l.step_factor, 1.5);
  EXPECT_GE(l.chi_factor, 1.0);
  EXPECT_LT(l.chi_factor, 1.6);
}

// The stated model is a floor: innovations smaller than stated leave scale 1
// (never narrower than the quantisation); a larger floor (what the
// calibration stated) holds too.
TEST(Learning, ScaleIsNeverBelowTheStatedModel) {
  Rng rng(8);
  std::vector<double> z(2000);
  for (double& v : z) v = 0.4 * rng.normal();
  EXPECT_EQ(learn(z, 50).scale, 1.0);
  EXPECT_EQ(learn(z, 50, 2.5).scale, 2.5);
  EXPECT_NEAR(learn(z, 50).mad_scale, 0.4, 0.03);
}

// A median and MAD: a few gross outliers (a slip in the learning phase) move
// the scale little.
TEST(Learning, ScaleIsRobustToOutliers) {
  Rng rng(9);
  std::vector<double> z(2000);
  for (double& v : z) v = 2.0 * rng.normal();
  for (int k = 0; k < 40; ++k) z[static_cast<size_t>(50 * k)] = 500.0;
  EXPECT_NEAR(learn(z, 50).mad_scale, 2.0, 0.15);
}

// AR(1) innovations z_k = rho z_{k-1} + sqrt(1 - rho^2) w_k (unit variance):
// a batch mean of B samples has variance (1/B) [(1 + rho) / (1 - rho) -
// 2 rho (1 - rho^B) / (B (1 - rho)^2)], so B var = 8.2 for rho = 0.8, B = 50;
// the factor used is that times (mad / scale)^2, widened by one standard
// error sqrt(2 / (batches - 1)).
TEST(Learning, StepFactorOfCorrelatedInnovationsIsTheBatchMeansVariance) {
  Rng rng(10);
  const double rho = 0.8;
  const int n = 20000, B = 50;
  std::vector<double> z(n);
  double prev = rng.normal();
  for (double& v : z) v = prev = rho * prev + std::sqrt(1.0 - rho * rho) * rng.normal();
  const LearnedScale l = learn(z, B);
  const double batch_var = (1.0 + rho) / (1.0 - rho) - 2.0 * rho * (1.0 - std::pow(rho, B)) / (B * (1.0 - rho) * (1.0 - rho));
  EXPECT_NEAR(batch_var, 8.2, 1e-3);
  const double r = l.mad_scale / l.scale;
  const double expected = batch_var * r * r * (1.0 + std::sqrt(2.0 / (n / B - 1)));
  EXPECT_NEAR(l.step_factor, expected, 0.15 * expected);
  EXPECT_NEAR(l.effective_samples, n / batch_var, 0.2 * n / batch_var);
}

// The step test's factor along a signature h: independent innovations give
// 1 whatever h (up to the widening by one standard error); AR(1) ones with a
// constant h the batch-means variance factor of the test above (8.2); a
// learnt bias is taken off first.
TEST(Learning, MatchedSumFactorOfIndependentAndCorrelatedInnovations) {
  Rng rng(11);
  const int B = 50, batches = 40;
  std::vector<MatchedBatch> iid(batches), ar(batches);
  double prev = rng.normal();
  const double rho = 0.8;
  for (int b = 0; b < batches; ++b)
    for (int j = 0; j < B; ++j) {
      const double h = std::sin(0.1 * (b * B + j)) + 0.3;  // a signature that varies along the path
      const double z = 2.0 + 3.0 * rng.normal();             // bias 2, scale 3
      iid[static_cast<size_t>(b)].h += h, iid[static_cast<size_t>(b)].hz += h * z, iid[static_cast<size_t>(b)].hh += h * h;
      prev = rho * prev + std::sqrt(1.0 - rho * rho) * rng.normal();
      ar[static_cast<size_t>(b)].h += 1.0, ar[static_cast<size_t>(b)].hz += prev, ar[static_cast<size_t>(b)].hh += 1.0;
    }
  const double widen = 1.0 + std::sqrt(2.0 / (batches - 1));
  const double f_iid = matched_sum_factor(batches, 2.0, 3.0, [&](int b) { return iid[static_cast<size_t>(b)]; });
  EXPECT_GE(f_iid, 1.0);
  EXPECT_LT(f_iid, 1.6 * widen);
  // The bias not taken off inflates it: the test would be the less sensitive.
  EXPECT_GT(matched_sum_factor(batches, 0.0, 3.0, [&](int b) { return iid[static_cast<size_t>(b)]; }), 3.0 * f_iid);
  const double f_ar = matched_sum_factor(batches, 0.0, 1.0, [&](int b) { return ar[static_cast<size_t>(b)]; });
  EXPECT_NEAR(f_ar, 8.2 * widen, 0.35 * 8.2 * widen);
  EXPECT_EQ(matched_sum_factor(1, 0.0, 1.0, [&](int b) { return ar[static_cast<size_t>(b)]; }), 1.0);
}

// The chi-square quantile at other degrees of freedom from the normal
// quantile of the monitor's threshold (Wilson-Hilferty) against Boost's.
TEST(Learning, WilsonHilfertyQuantileAgreesWithTheExactOne) {
  const double p = 0.5 * 0.01 / 720000.0;
  const double zp = wilson_hilferty_normal_quantile(250, chi2_upper_quantile(250, p));
  for (double dof : {250.0, 120.0, 60.0}) {
    const double exact = chi2_upper_quantile(dof, p);
    EXPECT_NEAR(chi2_quantile_wilson_hilferty(dof, zp), exact, 5e-3 * exact) << dof;
  }
  // Fewer degrees of freedom: within 2 %, and above the exact one (a wider test).
  const double exact = chi2_upper_quantile(25.0, p), wh = chi2_quantile_wilson_hilferty(25.0, zp);
  EXPECT_GE(wh, exact);
  EXPECT_LT(wh, 1.02 * exact);
}

// A robot noisier than stated (reading noise 4e-5 rad the monitor is not
// told of): without learning, false alarms; with it, none, and the learnt
// scale is sqrt(q^2 / 12 + 4e-5^2) / sqrt(q^2 / 12) (the ML residual carries
// the reading noise one to one; the parameters are known so well here that
// the filter adds nothing to the innovation's variance).
TEST(MonitorLearning, LearnsTheScaleOfANoisierRobotAndRaisesNoAlarm) {
  testing::CircleStream cs;
  cs.noise_rad = 4e-5;
  const Geometry base = MonitorSettings{}.geometry;
  const auto healthy = [&](double) { return base; };
  MonitorSettings s = testing::settings_without_map();
  for (int k = 0; k < kNumParams; ++k) s.prior_sigma[static_cast<size_t>(k)] = is_offset(k) ? 1e-9 : 1e-8;
  s.thermal_growth_mm = 0.0;
  s.offset_drift_rad = 0.0;
  s.learning_s = 0.0;
  {
    const MonitorModel m = make_monitor_model(s);
    auto d = std::make_unique<MonitorData>(make_monitor_data(m));
    EXPECT_GT(run_circle(m, *d, 30.0, healthy, cs).alarm_times.size(), 0u) << "the test could not fail";
  }
  s.learning_s = 8.0;
  const MonitorModel m = make_monitor_model(s);
  auto d = std::make_unique<MonitorData>(make_monitor_data(m));
  const auto run = run_circle(m, *d, 60.0, healthy, cs);
  EXPECT_TRUE(run.alarm_times.empty()) << run.alarm_times.size() << " alarms, first at " << run.alarm_times.front();
  EXPECT_FALSE(d->learning);
  // Learning ends after its 8 s and the review of what it learnt (monitor.hpp), within 10 s.
  EXPECT_GT(d->learning_end_s, 8.0);
  EXPECT_LE(d->learning_end_s, 10.0);
  const double expected = std::sqrt(m.sigma_rad * m.sigma_rad + 4e-5 * 4e-5) / m.sigma_rad;
  EXPECT_NEAR(d->learned.mad_scale, expected, 0.05 * expected);
  EXPECT_NEAR(d->learned.median, 0.0, 0.1 * expected);
  EXPECT_GE(d->noise_scale, d->learned.mad_scale);
}

// A monitor that starts from an estimate a calibration's 1-sigma off (20 um
// and 200 urad): the review replays the learnt samples as the monitor tests
// them, so the scale it learns is the one the live innovations then show
// (their robust scale after learning, in the stated units, cross-checked
// within 15 %), here that of readings with quantisation only (about 1: the ML
// residual carries the reading error one to one); no alarm in 60 s and the
// learning phase, review included, ends within 10 s.
TEST(MonitorLearning, TheReviewLearnsTheScaleTheLiveInnovationsShow) {
  MonitorSettings s = testing::settings_without_map();
  for (int k = 0; k < kNumParams; ++k) s.prior_sigma[static_cast<size_t>(k)] = is_offset(k) ? 2e-4 : 0.02;
  Geometry actual = s.geometry;
  actual[kLa1] += 0.02;
  actual[kLb2] -= 0.02;
  actual[kDth1] += 2e-4;
  actual[kDth3] -= 2e-4;
  const MonitorModel m = make_monitor_model(s);
  auto d = std::make_unique<MonitorData>(make_monitor_data(m));
  const auto run = run_circle(m, *d, 60.0, [&](double) { return actual; });
  EXPECT_TRUE(run.alarm_times.empty()) << run.alarm_times.size() << " alarms, first at " << run.alarm_times.front();
  ASSERT_FALSE(d->learning);
  EXPECT_LE(d->learning_end_s, 10.0);
  // The live innovations of the last 30 s, in the stated units, about their median.
  std::vector<double> dev(run.z.end() - 3000, run.z.end());
  for (double& v : dev) v *= d->noise_scale;
  std::nth_element(dev.begin(), dev.begin() + 1500, dev.end());
  const double median = dev[1500];
  for (double& v : dev) v = std::abs(v - median);
  std::nth_element(dev.begin(), dev.begin() + 1500, dev.end());
  EXPECT_NEAR(d->learned.mad_scale, 1.4826 * dev[1500], 0.15 * d->learned.mad_scale);
  EXPECT_NEAR(d->learned.mad_scale, 1.0, 0.2);
}

// On a drive bus polled at 250 Hz nearly every cycle accepts a sample, so
// few cycles are free for the review: it takes more of the learnt samples a
// cycle, also beside a live sample (the same share of a cycle 16 times as
// long as at 4 kHz), and the learning phase, review included, still ends
// within 10 s with no alarm (measured 8.48 s; with the 4 kHz budget on free
// cycles only it had not ended after 20 s).
TEST(MonitorLearning, TheReviewEndsWithinTenSecondsAtADriveBussRate) {
  testing::CircleStream cs;
  cs.rate_hz = 250.0;
  MonitorSettings s = testing::settings_without_map();
  s.cycle_hz = cs.rate_hz;
  s.decimation = 1;  // as gpm's monitor sets it for at most 200 samples a second (run/monitor_run.cpp)
  const MonitorModel m = make_monitor_model(s);
  auto d = std::make_unique<MonitorData>(make_monitor_data(m));
  const Geometry base = s.geometry;
  const auto run = run_circle(m, *d, 20.0, [&](double) { return base; }, cs);
  EXPECT_TRUE(run.alarm_times.empty()) << run.alarm_times.size() << " alarms, first at " << run.alarm_times.front();
  ASSERT_FALSE(d->learning);
  EXPECT_GT(d->learning_end_s, 8.0);
  EXPECT_LE(d->learning_end_s, 10.0);
  EXPECT_GT(d->learned.samples, 1000);  // most cycles accepted a sample
  std::printf("learning ended at %.2f s, %d samples learnt\n", d->learning_end_s, d->learned.samples);
}

// No alarm while learning, even for a gross slip inside the learning phase
// (without learning the same slip raises one); the learning phase ends on
// time.
TEST(MonitorLearning, NoAlarmDuringLearning) {
  const Geometry base = MonitorSettings{}.geometry;
  const auto slip_at_4s = [&](double t) {
    Geometry g = base;
    if (t >= 4.0) g[kDth2] += 1e-3;
    return g;
  };
  MonitorSettings s;
  s.learning_s = 0.0;
  {
    const MonitorModel m = make_monitor_model(s);
    auto d = std::make_unique<MonitorData>(make_monitor_data(m));
    const auto run = run_circle(m, *d, 9.0, slip_at_4s);
    ASSERT_FALSE(run.alarm_times.empty()) << "the test could not fail";
    EXPECT_LT(run.alarm_times.front(), 5.0);
  }
  s.learning_s = 9.0;
  const MonitorModel m = make_monitor_model(s);
  auto d = std::make_unique<MonitorData>(make_monitor_data(m));
  const auto run = run_circle(m, *d, 9.0, slip_at_4s);
  EXPECT_TRUE(run.alarm_times.empty());
  EXPECT_TRUE(d->learning);
}

// After learning on the stated 17-bit robot the scale stays near 1 and a
// 1e-4 rad slip of each encoder is found within 1 s and named.
TEST(MonitorLearning, SlipAfterLearningIsFoundWithinOneSecondAndNamed) {
  MonitorSettings s = testing::settings_without_map();
  s.learning_s = 8.0;
  const MonitorModel m = make_monitor_model(s);
  for (int joint = 0; joint < 3; ++joint) {
    auto d = std::make_unique<MonitorData>(make_monitor_data(m));
    const Geometry base = m.settings.geometry;
    const auto run = run_circle(m, *d, 40.0, [&](double t) {
      Geometry g = base;
      if (t >= 30.0) g[dth(joint)] += 1e-4;
      return g;
    });
    EXPECT_LT(d->learned.scale, 1.2) << "joint " << joint + 1;
    ASSERT_FALSE(run.alarm_times.empty()) << "joint " << joint + 1;
    EXPECT_GE(run.alarm_times[0], 30.0);
    EXPECT_LT(run.alarm_times[0], 31.0) << "joint " << joint + 1;
    ASSERT_FALSE(run.alarms.empty());
    EXPECT_EQ(run.alarms[0].param, dth(joint)) << describe_alarm(run.alarms[0]);
  }
}

// After learning, the step factors go on learning from the batches of
// operation (MonitorSettings::refine_step_factors). On readings with a
// structured error (a transmission error of 2e-5 rad at the gear's
// harmonics, correlated from sample to sample): the batch terms of
// operation are in the learning phase's units (their mean, summed by the
// live monitor as samples leave its window, agrees with the mean of the
// review's replayed terms within their statistical spread: about 22 terms,
// 30 %), and with five times the terms the factor narrows (its widening by
// one standard error shrinks: measured 9.9 -> 7.2); no alarm on the healthy
// robot either way.
TEST(MonitorLearning, TheStepFactorsGoOnLearningInOperation) {
  testing::CircleStream cs;
  cs.transmission_rad = 2e-5;
  const auto healthy = [base = MonitorSettings{}.geometry](double) { return base; };
  MonitorSettings s = testing::settings_without_map();
  s.refine_step_factors = false;
  const testing::FreshRun without = testing::run_fresh(s, 40.0, healthy, cs);
  s.refine_step_factors = true;
  const testing::FreshRun with = testing::run_fresh(s, 40.0, healthy, cs);
  const MonitorData* learnt = without.data.get();
  const MonitorData* d = with.data.get();
  EXPECT_TRUE(without.run.alarm_times.empty());
  EXPECT_TRUE(with.run.alarm_times.empty());
  const MatchedTerms& before = learnt->step_terms[kDth3];
  const MatchedTerms& after = d->step_terms[kDth3];
  EXPECT_EQ(learnt->operation_batches, 0);
  ASSERT_GE(before.count, 15);
  // Every batch of operation that left the window: (accepted - learnt - window) / batch.
  const int operation = after.count - before.count;
  EXPECT_EQ(operation, d->operation_batches);
  EXPECT_GE(operation, 4 * before.count);
  const double mean_learnt = before.sum / before.count;
  const double mean_operation = (after.sum - before.sum) / operation;
  std::printf("dth3 batch terms: learnt %d, mean %.2f; operation %d, mean %.2f; factor %.2f -> %.2f\n", before.count,
              mean_learnt, operation, mean_operation, learnt->step_factor[kDth3], d->step_factor[kDth3]);
  EXPECT_GT(mean_learnt, 2.0);  // the readings are correlated: the test could fail
  EXPECT_NEAR(mean_operation / mean_learnt, 1.0, 0.3 * 1.5);
  EXPECT_DOUBLE_EQ(d->step_factor[kDth3], std::max(d->step_floor[kDth3], matched_factor(after)));
  EXPECT_LT(d->step_factor[kDth3], 0.85 * learnt->step_factor[kDth3]);
}

}  // namespace
}  // namespace gpm::calib::monitor
