// Tests of calib/monitor/monitor.cpp on generated readings (circle_stream.hpp:
// circle of radius 60 mm around (216.5, 250), period 4 s, 1 kHz, 17-bit
// quantisation): the noise and threshold derivation, an offset jump detected
// and explained, no false alarm in 5 minutes (the 1 h run is
// test_monitor_long.cpp), thermal growth tracked without alarm, and the
// filter's 1-sigma against the Cramer-Rao bound of calib/crb.hpp.
#include "calib/monitor/monitor.hpp"

#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "calib/crb.hpp"
#include "calib/chi_square.hpp"
#include "models/errors.hpp"
#include "tests/calib/monitor/run_circle.hpp"

namespace gpm::calib::monitor {
namespace {

using testing::run_circle;

TEST(Monitor, NoiseAndThresholdFollowFromTheStatedRates) {
  MonitorSettings s;
  s.reading.noise_rad = 1e-5;
  const MonitorModel m = make_monitor_model(s);
  const double q = 2.0 * std::numbers::pi / 131072.0;
  EXPECT_NEAR(m.sigma_rad, std::sqrt(q * q / 12.0 + 1e-10), 1e-18);
  // One window test per accepted sample, at most cycle_hz / decimation per second.
  EXPECT_DOUBLE_EQ(m.tests_per_hour, 3600.0 * 1000.0 / 5.0);
  EXPECT_NEAR(m.p_window, 0.01 / 720000.0, 1e-20);
  // The two tests share the rate; the step test's p is split over its
  // n_free * W (parameter, onset) hypotheses.
  EXPECT_NEAR(chi2_survival(s.window, m.threshold), m.p_window / 2, 1e-6 * m.p_window);
  EXPECT_NEAR(chi2_survival(1, m.glr_threshold), m.p_window / (2 * 11 * s.window), 1e-6 * m.p_window / 4400);
  EXPECT_GT(m.threshold, 1.5 * s.window);
}

TEST(Monitor, RejectsBadSettingsWithOneLine) {
  MonitorSettings s;
  s.window = 1000;
  EXPECT_THROW(make_monitor_model(s), InputError);
  s = MonitorSettings{};
  s.reading.encoder_bits = 0;
  EXPECT_THROW(make_monitor_model(s), InputError);  // no noise at all
  s = MonitorSettings{};
  s.false_alarms_per_hour = 0.0;
  EXPECT_THROW(make_monitor_model(s), InputError);
  s = MonitorSettings{};
  s.estimate.reset();
  EXPECT_THROW(make_monitor_model(s), InputError);
}

// (a) A jump of 1e-4 rad in one offset at t = 30 s.
TEST(Monitor, OffsetJumpIsDetectedAndExplainedByThatOffset) {
  const MonitorModel m = make_monitor_model(MonitorSettings{});
  for (int joint = 0; joint < 3; ++joint) {
    MonitorData d = make_monitor_data(m);
    const Geometry base = m.settings.geometry;
    const auto run = run_circle(m, d, 40.0, [&](double t) {
      Geometry g = base;
      if (t >= 30.0) g[dth(joint)] += 1e-4;
      return g;
    });
    ASSERT_FALSE(run.alarm_times.empty()) << "joint " << joint + 1;
    ASSERT_FALSE(run.alarms.empty()) << "joint " << joint + 1;
    EXPECT_GE(run.alarm_times[0], 30.0);
    // Goal: within 1 s. (Joint 3 is the slow one: at (156.5, 250), where the
    // robot is at 30 s, its reading barely moves the ML residual.)
    EXPECT_LT(run.alarm_times[0], 31.0) << "joint " << joint + 1;
    const Alarm& a = run.alarms[0];
    EXPECT_EQ(a.param, dth(joint)) << describe_alarm(a);
    EXPECT_NEAR(a.delta, 1e-4, 1.5e-5) << describe_alarm(a);
    EXPECT_NEAR(a.onset_s, 30.0, 0.1) << describe_alarm(a);
    // Once explained and applied, the change raises no further alarm.
    EXPECT_EQ(run.alarm_times.size(), 1u) << "joint " << joint + 1;
    EXPECT_NE(describe_alarm(a).find(fmt::format("offset jump on joint {}", joint + 1)), std::string::npos);
  }
}

// (a') The same jump at 16 points of one period of the circle (every 0.25 s
// from 5 s), on each joint: always detected within 1 s and explained by that
// joint's offset.
TEST(Monitor, OffsetJumpIsDetectedAnywhereOnTheCircle) {
  const MonitorModel m = make_monitor_model(testing::settings_without_map());
  const Geometry base = m.settings.geometry;
  double worst = 0.0;
  for (int joint = 0; joint < 3; ++joint)
    for (int k = 0; k < 16; ++k) {
      const double t0 = m.settings.learning_s + 5.0 + 0.25 * k;  // after the learning phase
      auto d = std::make_unique<MonitorData>(make_monitor_data(m));
      const auto run = run_circle(m, *d, t0 + 2.6, [&](double t) {
        Geometry g = base;
        if (t >= t0) g[dth(joint)] += 1e-4;
        return g;
      });
      ASSERT_FALSE(run.alarm_times.empty()) << "joint " << joint + 1 << " at " << t0;
      ASSERT_FALSE(run.alarms.empty()) << "joint " << joint + 1 << " at " << t0;
      EXPECT_GE(run.alarm_times[0], t0);
      EXPECT_LT(run.alarm_times[0], t0 + 1.0) << "joint " << joint + 1 << " at " << t0;
      EXPECT_EQ(run.alarms[0].param, dth(joint)) << "at " << t0 << ": " << describe_alarm(run.alarms[0]);
      worst = std::max(worst, run.alarm_times[0] - t0);
    }
  std::printf("worst detection delay %.3f s\n", worst);
}

// (b) No false alarm in 5 minutes of motion without events; the accepted
// innovations behave as independent draws of variance 1 in the stated units.
TEST(Monitor, NoFalseAlarmInFiveMinutesAndInnovationsAreWhite) {
  const MonitorModel m = make_monitor_model(testing::settings_without_map());
  MonitorData d = make_monitor_data(m);
  const Geometry g = m.settings.geometry;
  const auto run = run_circle(m, d, 300.0, [&](double) { return g; });
  EXPECT_EQ(run.alarm_times.size(), 0u);
  double s1 = 0.0, s2 = 0.0, lag = 0.0;
  for (size_t j = 0; j < run.z.size(); ++j) {
    s1 += run.z[j];
    s2 += run.z[j] * run.z[j];
    if (j) lag += run.z[j] * run.z[j - 1];
  }
  const double n = static_cast<double>(run.z.size());
  EXPECT_GT(n, 25000.0);  // ~100 accepted samples per second
  EXPECT_NEAR(s1 / n, 0.0, 0.05);
  // z is in units of the learnt scale (its upper bound, at least the stated
  // one): in the stated units the innovations have unit variance, and the
  // learnt scale widens the test by at most 15 % on a robot as stated.
  EXPECT_NEAR(s2 / n * d.noise_scale * d.noise_scale, 1.0, 0.15);
  EXPECT_GE(d.noise_scale, 1.0);
  EXPECT_LE(d.noise_scale, 1.15);
  EXPECT_LT(std::abs(lag / s2), 0.1);  // lag-1 autocorrelation
}

// Gaussian reading noise on top of the quantisation enters sigma; the
// innovations stay normalised, no false alarm, and a jump is still named.
TEST(Monitor, AdditiveReadingNoiseIsPartOfSigma) {
  MonitorSettings s = testing::settings_without_map();
  s.reading.noise_rad = 2e-5;
  const MonitorModel m = make_monitor_model(s);
  MonitorData d = make_monitor_data(m);
  testing::CircleStream cs;
  cs.noise_rad = 2e-5;
  const Geometry base = s.geometry;
  const auto run = run_circle(
      m, d, 150.0,
      [&](double t) {
        Geometry g = base;
        if (t >= 120.0) g[kDth2] += 1e-4;
        return g;
      },
      cs);
  double s2 = 0.0;
  for (double z : run.z) s2 += z * z;
  EXPECT_NEAR(s2 / static_cast<double>(run.z.size()), 1.0, 0.15);
  ASSERT_EQ(run.alarm_times.size(), 1u);
  EXPECT_GE(run.alarm_times[0], 120.0);
  EXPECT_LT(run.alarm_times[0], 121.0);
  ASSERT_EQ(run.alarms.size(), 1u);
  EXPECT_EQ(run.alarms[0].param, kDth2) << describe_alarm(run.alarms[0]);
}

// (c) Thermal growth of 20 um per link, first order with tau = 60 s.
// One circle observes the common growth of the links but hardly any link on
// its own: how the filter splits what it sees between the growth and the
// other parameters depends on how well the calibration pinned those (their
// prior). The monitor starts here from a calibration of 1 um and 5e-6 rad
// (1-sigma); with the looser defaults (2 um, 2e-5 rad) the worst error is
// about 3.0 um (README.md).
TEST(Monitor, ThermalGrowthIsTrackedWithinThreeMicrometresWithoutAlarm) {
  MonitorSettings s;
  for (int i = 0; i < kNumParams; ++i) s.prior_sigma[static_cast<size_t>(i)] = is_offset(i) ? 5e-6 : 0.001;
  const MonitorModel m = make_monitor_model(s);
  MonitorData d = make_monitor_data(m);
  const Geometry base = m.settings.geometry;
  auto actual = [&](double t) {
    Geometry g = base;
    for (int i = 0; i < 3; ++i) {
      g[la(i)] += 0.020 * (1.0 - std::exp(-t / 60.0));
      g[lb(i)] += 0.020 * (1.0 - std::exp(-t / 60.0));
    }
    return g;
  };
  const auto run = run_circle(m, d, 240.0, actual);
  EXPECT_EQ(run.alarm_times.size(), 0u);
  double worst = 0.0;
  for (const auto& [t, e] : run.estimates) {
    if (t < 10.0) continue;
    const Geometry g = actual(t);
    for (int i = kLa1; i <= kLb3; ++i) worst = std::max(worst, std::abs(e.value[static_cast<size_t>(i)] - g[i]));
  }
  std::printf("worst tracking error %.2f um\n", 1e3 * worst);
  EXPECT_LT(worst, 0.003);
  // and it did move: the final estimate carries most of the 20 um
  const auto& last = run.estimates.back().second;
  for (int i = kLa1; i <= kLb3; ++i) EXPECT_GT(last.value[static_cast<size_t>(i)] - base[i], 0.015);
}

// (d) Without drift the filter is the recursive form of least squares: its
// 1-sigma equals the Cramer-Rao bound of the samples it absorbed.
TEST(Monitor, FilterSigmaAgreesWithTheCramerRaoBound) {
  MonitorSettings s = testing::settings_without_map();
  s.estimate = parse_param_list("la1,la2,la3,dth1,dth2,dth3", "test");
  for (int i = 0; i < kNumParams; ++i) s.prior_sigma[static_cast<size_t>(i)] = is_offset(i) ? 1e-3 : 0.1;
  s.thermal_tau_s = std::numeric_limits<double>::infinity();
  const MonitorModel m = make_monitor_model(s);
  MonitorData d = make_monitor_data(m);
  const Geometry g = s.geometry;
  const auto run = run_circle(m, d, 10.0, [&](double) { return g; });
  monitor_flush(m, d);
  ASSERT_EQ(d.filtered, static_cast<long>(run.accepted.size()));
  const auto crb = crb_sigma(g, s.estimate, run.accepted, m.sigma_rad);
  const Estimate e = monitor_estimate(m, d);
  for (int i = 0; i < kNumParams; ++i) {
    if (!s.estimate.test(static_cast<size_t>(i))) continue;
    const double ratio = e.sigma[static_cast<size_t>(i)] / crb[static_cast<size_t>(i)];
    std::printf("%s filter/CRB %.3f\n", std::string(param_name(i)).c_str(), ratio);
    EXPECT_NEAR(ratio, 1.0, 0.2) << param_name(i);
  }
}

}  // namespace
}  // namespace gpm::calib::monitor
