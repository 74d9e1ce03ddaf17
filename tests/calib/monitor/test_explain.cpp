// Tests of calib/monitor/explain.cpp on a hand-built window: innovations made
// exactly of one parameter's column times a change from a known onset are
// explained by that parameter, onset and (prior-shrunk) change; a window of
// zeros before the onset does not move the onset; the step statistic against
// closed forms, with and without its shortest step, and the filter's shared
// error in its denominator (by default the shared-error bound, and without it).
#include "calib/monitor/explain.hpp"

#include <memory>

#include <gtest/gtest.h>

#include "models/errors.hpp"
#include "models/rng.hpp"

namespace gpm::calib::monitor {
namespace {

TEST(Explain, FindsTheParameterOnsetAndChangeOfAHandBuiltWindow) {
  const MonitorModel m = make_monitor_model(MonitorSettings{});
  for (int truth : {kLa2, kDth3, kXa3}) {
    MonitorData d = make_monitor_data(m);
    Rng rng(7 + static_cast<unsigned>(truth));
    const int n = 60, onset = 25;
    const double delta = is_offset(truth) ? 1e-4 : 0.02;
    double s_hh = 0.0;
    for (int j = 0; j < n; ++j) {
      ParamRow dz;
      for (int i = 0; i < kNumParams; ++i) dz[i] = rng.normal() * (is_offset(i) ? 5e3 : 30.0);
      d.dz[static_cast<size_t>(j)] = dz;
      d.t[static_cast<size_t>(j)] = 0.01 * j;
      d.z[static_cast<size_t>(j)] = j >= onset ? -dz[truth] * delta : 0.0;
      if (j >= onset) s_hh += dz[truth] * dz[truth];
    }
    d.head = n;
    d.count = n;
    Alarm a;
    a.t_s = 0.01 * (n - 1);  // raised at the window's last sample
    explain_window(m, d, a);
    EXPECT_EQ(a.param, truth);
    EXPECT_DOUBLE_EQ(a.onset_s, 0.01 * onset);
    const double d0 = is_offset(truth) ? m.settings.jump_offset_rad : m.settings.jump_length_mm;
    EXPECT_NEAR(a.delta, delta * s_hh / (s_hh + 1.0 / (d0 * d0)), 1e-9 * std::abs(delta));
    // the prior shrinks the fit: S_zh^2 / (S_hh + d0^-2) of S_zz = delta^2 S_hh
    EXPECT_NEAR(a.explained, s_hh / (s_hh + 1.0 / (d0 * d0)), 1e-9);
  }
}

TEST(Explain, OnsetIsNeverAfterTheAlarm) {
  // Samples after the alarm (explain_samples of them) are in the window; a
  // change they alone carry must not place the onset after the alarm.
  const MonitorModel m = make_monitor_model(MonitorSettings{});
  MonitorData d = make_monitor_data(m);
  Rng rng(3);
  const int n = 60, alarm_at = 20, onset = 40;
  for (int j = 0; j < n; ++j) {
    ParamRow dz;
    for (int i = 0; i < kNumParams; ++i) dz[i] = rng.normal() * (is_offset(i) ? 5e3 : 30.0);
    d.dz[static_cast<size_t>(j)] = dz;
    d.t[static_cast<size_t>(j)] = 0.01 * j;
    d.z[static_cast<size_t>(j)] = j >= onset ? -dz[kLa2] * 0.02 : 0.0;
  }
  d.head = n;
  d.count = n;
  Alarm a;
  a.t_s = 0.01 * alarm_at;
  explain_window(m, d, a);
  EXPECT_LE(a.onset_s, a.t_s);
  a = Alarm{};
  a.t_s = 0.01 * (n - 1);
  explain_window(m, d, a);  // the same window explained at its end finds the onset
  EXPECT_DOUBLE_EQ(a.onset_s, 0.01 * onset);
}

// The step test's shortest step (settings.step_min_samples): in a window of
// zero innovations with dz = 1 along la1 only, one sample of z = 8 at the end
// scores 8^2 = 64 when any onset counts, but over the shortest step of 10
// only 8^2 / 10 = 6.4; a step of 10 samples of z = 2.5 scores
// (10 x 2.5)^2 / 10 = 62.5 either way; clipped at 5 the one sample scores
// 5^2 and the step still 62.5 (closed forms, P = 0).
TEST(StepStatistic, OneSampleOffIsNoStepOfTheShortestLength) {
  const auto statistic = [](int min_samples, int step_length, double z, double clip = 0.0) {
    MonitorSettings s;
    s.step_min_samples = min_samples;
    s.step_clip = clip;
    const MonitorModel m = make_monitor_model(s);
    auto w = std::make_unique<FilterWindow>();
    w->P.setZero();
    const int n = 100;
    for (int j = 0; j < n; ++j) {
      ParamRow dz = ParamRow::Zero();
      dz[kLa1] = 1.0;
      w->dz[static_cast<size_t>(j)] = dz;
      w->z[static_cast<size_t>(j)] = j >= n - step_length ? z : 0.0;
    }
    w->head = n;
    w->count = n;
    return step_statistic(m, *w);
  };
  EXPECT_NEAR(statistic(1, 1, 8.0), 64.0, 1e-12);
  EXPECT_NEAR(statistic(10, 1, 8.0), 6.4, 1e-12);
  EXPECT_NEAR(statistic(1, 10, 2.5), 62.5, 1e-12);
  EXPECT_NEAR(statistic(10, 10, 2.5), 62.5, 1e-12);
  // Clipped at 5 (settings.step_clip): the gross sample counts as 5, the
  // moderate step as it is.
  EXPECT_NEAR(statistic(1, 1, 8.0, 5.0), 25.0, 1e-12);
  EXPECT_NEAR(statistic(10, 10, 2.5, 5.0), 62.5, 1e-12);
  MonitorSettings bad;
  bad.step_min_samples = bad.window + 1;
  EXPECT_THROW(make_monitor_model(bad), InputError);
}

// The error of the filter that all innovations of a window share adds to the
// variance of the step test's S_zh = sum dz_i z: without
// settings.step_shared_bound S_hh^2 P_ii (the error along parameter i alone);
// with it (the default) the smaller of that and the Cauchy-Schwarz bound
// (sum |dz_i| z_filter)^2 (any error, each sample's share of it known). Window of 100 samples with dz = 1 along
// la1 only, a step of 10 samples of z = 2.5 at its end (shortest step 10:
// the onset is the step's), closed forms: (10 x 2.5)^2 / (10 + min(100
// z_filter^2, 100 var)), and without the bound (10 x 2.5)^2 / (10 (1 + 10 var)).
TEST(StepStatistic, TheSharedFilterErrorIsTheSmallerOfItsMarginalAndItsBound) {
  MonitorSettings marginal;
  marginal.step_shared_bound = false;
  const MonitorModel m = make_monitor_model(MonitorSettings{});
  const MonitorModel m_default = make_monitor_model(marginal);
  int k_la1 = -1;
  for (int k = 0; k < m.n_free; ++k)
    if (m.free_index[static_cast<size_t>(k)] == kLa1) k_la1 = k;
  ASSERT_GE(k_la1, 0);
  const auto statistic = [&](double var, double z_filter, const MonitorModel& model) {
    auto w = std::make_unique<FilterWindow>();
    w->P.setZero();
    const double sc = m.scale[static_cast<size_t>(k_la1)];
    w->P(k_la1, k_la1) = var * sc * sc;  // (P is in scaled units)
    const int n = 100;
    for (int j = 0; j < n; ++j) {
      ParamRow dz = ParamRow::Zero();
      dz[kLa1] = 1.0;
      w->dz[static_cast<size_t>(j)] = dz;
      w->z_filter[static_cast<size_t>(j)] = z_filter;
      w->z[static_cast<size_t>(j)] = j >= n - 10 ? 2.5 : 0.0;
    }
    w->head = n;
    w->count = n;
    return step_statistic(model, *w);
  };
  // A parameter the filter knows only along directions the window does not
  // see (large P_ii, no share in the innovations): not diluted (the marginal
  // alone gave 625 / (10 + 100) = 5.68).
  EXPECT_NEAR(statistic(1.0, 0.0, m), 62.5, 1e-12);
  // Innovations sharing the filter's error, parameter i known exactly: the marginal.
  EXPECT_NEAR(statistic(0.0, 0.5, m), 62.5, 1e-12);
  EXPECT_NEAR(statistic(0.01, 0.05, m), 625.0 / 10.25, 1e-12);  // the bound is smaller
  EXPECT_NEAR(statistic(0.01, 0.2, m), 625.0 / 11.0, 1e-12);    // the marginal is smaller
  // Without the bound the marginal alone, whatever the samples' shares.
  EXPECT_NEAR(statistic(1.0, 0.0, m_default), 625.0 / 110.0, 1e-12);
  EXPECT_NEAR(statistic(0.01, 0.05, m_default), 625.0 / 11.0, 1e-12);
}

}  // namespace
}  // namespace gpm::calib::monitor
