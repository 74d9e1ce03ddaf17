// bench_monitor: per-cycle cost of calib/monitor's monitor_step() at the
// servo rate (goal < 20 us, 50x headroom at 1 kHz), on the circle of the
// monitor tests (radius 60 mm around (216.5, 250), period 4 s, 17-bit
// readings). Three cases:
//   BM_MonitorStepAverage   every cycle of the stream, as a controller calls it
//                           (one cycle in `decimation` does the work);
//   BM_MonitorStepAccepted  only cycles whose sample is accepted (window
//                           test, step test and a filter update): the worst
//                           regular cycle;
//   BM_MonitorStepOffTheMap a candidate cycle off the configuration map
//                           (config_map.hpp): the whole map searched;
//   BM_MonitorStepAlarm     the cycle that explains an alarm and re-baselines
//   BM_MonitorStepLearningEnd  the one cycle that ends the learning phase
//                           (the rare worst case).
//   BM_MonitorStepReview/0  the cycles of the review of the learning phase
//                           at a 4 kHz servo rate (/1: with the
//                           configuration map; /2: at a 250 Hz drive bus,
//                           where each cycle takes 16 times the review's
//                           work, 15 beside an accepted sample)
//                           (monitor.hpp), in turn: each replays learnt
//                           samples (a filter update, an innovation, the
//                           window's tests) or, on an accepted cycle, the
//                           live work only.
//   bench_monitor [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "calib/monitor/monitor.hpp"
#include "models/kinematics.hpp"

namespace {

using namespace gpm;
using namespace gpm::calib::monitor;

// Readings of the nominal robot on the circle, 17-bit quantised.
std::vector<Eigen::Vector3d> circle_readings(int n, double dth2_jump_at = 1e300, double centre_x = 216.5) {
  const double q = 2.0 * std::numbers::pi / 131072.0;
  std::vector<Eigen::Vector3d> out(static_cast<size_t>(n));
  for (int c = 0; c < n; ++c) {
    const double t = c / 1000.0, w = 2.0 * std::numbers::pi * t / 4.0;
    Geometry g = Geometry::gpm2002_nominal();
    if (t >= dth2_jump_at) g[kDth2] += 1e-4;
    const JointAngles ja = inverse_kinematics(g, Eigen::Vector2d(centre_x + 60 * std::cos(w), 250 + 60 * std::sin(w)));
    for (int i = 0; i < 3; ++i) out[static_cast<size_t>(c)][i] = std::round((ja.theta_a[i] - g.dth_(i)) / q) * q;
  }
  return out;
}

void BM_MonitorStepAverage(benchmark::State& state) {
  const MonitorModel m = make_monitor_model(MonitorSettings{});
  static const std::vector<Eigen::Vector3d> readings = circle_readings(8000);
  auto d = std::make_unique<MonitorData>(make_monitor_data(m));
  long c = 0;
  for (auto _ : state) {
    const auto k = static_cast<size_t>(c % 8000);
    benchmark::DoNotOptimize(monitor_step(m, *d, c / 1000.0, readings[k]));
    ++c;
  }
  state.counters["accepted_per_cycle"] = static_cast<double>(d->accepted) / static_cast<double>(d->cycles);
  state.counters["alarms"] = static_cast<double>(d->alarm_count);
}
BENCHMARK(BM_MonitorStepAverage)->Unit(benchmark::kMicrosecond);

void BM_MonitorStepAccepted(benchmark::State& state) {
  MonitorSettings s;
  s.decimation = 1;         // every cycle is a candidate ...
  s.min_motion_counts = 0;  // ... and accepted
  const MonitorModel m = make_monitor_model(s);
  static const std::vector<Eigen::Vector3d> readings = circle_readings(8000);
  auto d = std::make_unique<MonitorData>(make_monitor_data(m));
  long c = 0;
  for (auto _ : state) {
    // 5 ms apart on the path, as accepted samples are with the defaults
    const auto k = static_cast<size_t>((5 * c) % 8000);
    benchmark::DoNotOptimize(monitor_step(m, *d, 0.005 * c, readings[k]));
    ++c;
  }
  state.counters["accepted_per_cycle"] = static_cast<double>(d->accepted) / static_cast<double>(d->cycles);
}
BENCHMARK(BM_MonitorStepAccepted)->Unit(benchmark::kMicrosecond);

// After learning on the circle, cycles on a circle 20 mm aside: no learnt
// configuration within the map's radius, so each (a candidate: the last
// accepted sample is far) searches the whole map (config_map.hpp) and is not
// tested (the map's worst look-up).
void BM_MonitorStepOffTheMap(benchmark::State& state) {
  MonitorSettings s;
  s.map_radius_rad = 3e-3;  // the map on (off by default)
  const MonitorModel m = make_monitor_model(s);
  static const std::vector<Eigen::Vector3d> learnt = circle_readings(12000);
  static const std::vector<Eigen::Vector3d> aside = circle_readings(8000, 1e300, 236.5);
  auto d = std::make_unique<MonitorData>(make_monitor_data(m));
  long c = 0;
  for (; c < 12000 && d->learning; ++c) monitor_step(m, *d, c / 1000.0, learnt[static_cast<size_t>(c)]);
  if (!d->map_on) {
    state.SkipWithError("the map is not on after learning");
    return;
  }
  const long unmapped0 = d->unmapped;
  long timed = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(monitor_step(m, *d, c / 1000.0, aside[static_cast<size_t>(c % 8000)]));
    ++c, ++timed;
  }
  state.counters["unmapped_per_cycle"] = static_cast<double>(d->unmapped - unmapped0) / static_cast<double>(timed);
}
BENCHMARK(BM_MonitorStepOffTheMap)->Unit(benchmark::kMicrosecond);

// The accepted cycle with the realistic reading model (effects: realistic):
// motion corrections, clearance variance and the six cyclic-error
// coordinates in the filter (18 instead of 12).
void BM_MonitorStepAcceptedRealistic(benchmark::State& state) {
  MonitorSettings s;
  s.decimation = 1;
  s.min_motion_counts = 0;
  s.friction_stick_rad_s = 0.0;
  s.reading.skew_s = {0.0, 5e-5, 1e-4};
  s.reading.compliance_rad_per_Nm = {1e-4, 1e-4, 1e-4};
  s.reading.load.coulomb_Nm = {0.3, 0.3, 0.3};
  s.reading.load.viscous_Nm_s = {0.15, 0.15, 0.15};
  s.reading.cyclic_rad = {2e-5, 2e-5, 2e-5};
  s.reading.clearance_mm = {0.01, 0.01, 0.01};
  const MonitorModel m = make_monitor_model(s);
  static const std::vector<Eigen::Vector3d> readings = circle_readings(8000);
  auto d = std::make_unique<MonitorData>(make_monitor_data(m));
  const Eigen::Vector3d omega(0.3, -0.2, 0.25), tau(0.0, 0.5, -0.4);
  long c = 0;
  for (auto _ : state) {
    const auto k = static_cast<size_t>((5 * c) % 8000);
    benchmark::DoNotOptimize(monitor_step(m, *d, 0.005 * c, readings[k], omega, tau));
    ++c;
  }
  state.counters["accepted_per_cycle"] = static_cast<double>(d->accepted) / static_cast<double>(d->cycles);
  state.counters["filter_coordinates"] = m.n_state;
  // The constant speeds and torques do not fit the circle's readings: some
  // cycles alarm (the filter then waits), so compare timings at equal counts.
  state.counters["alarms"] = static_cast<double>(d->alarm_count);
}
BENCHMARK(BM_MonitorStepAcceptedRealistic)->Unit(benchmark::kMicrosecond);

void BM_MonitorStepAlarm(benchmark::State& state) {
  // Run up to the cycle before an alarm's explanation, then time that cycle.
  const MonitorModel m = make_monitor_model(MonitorSettings{});
  // (the jump after the learning phase: no alarm while learning)
  static const std::vector<Eigen::Vector3d> readings = circle_readings(13000, m.settings.learning_s + 3.0);
  MonitorData start = make_monitor_data(m);
  long c = 0;
  for (; c < 13000; ++c) {
    if (start.pending == 1 && start.cycles_since_accepted + 1 >= m.settings.decimation) break;
    monitor_step(m, start, c / 1000.0, readings[static_cast<size_t>(c)]);
  }
  auto d = std::make_unique<MonitorData>();
  for (auto _ : state) {
    state.PauseTiming();
    *d = start;
    state.ResumeTiming();
    const StepResult r = monitor_step(m, *d, c / 1000.0, readings[static_cast<size_t>(c)]);
    benchmark::DoNotOptimize(r);
    if (!r.explained) state.SkipWithError("the timed cycle did not explain an alarm");
  }
}
BENCHMARK(BM_MonitorStepAlarm)->Unit(benchmark::kMicrosecond);

// The one cycle that ends the learning phase (learning.hpp: medians, batch
// factors, the window restated).
void BM_MonitorStepLearningEnd(benchmark::State& state) {
  const MonitorModel m = make_monitor_model(MonitorSettings{});
  static const std::vector<Eigen::Vector3d> readings = circle_readings(10000);
  long end = -1;
  {
    auto dry = std::make_unique<MonitorData>(make_monitor_data(m));
    for (long c = 0; c < 10000 && end < 0; ++c)
      if (monitor_step(m, *dry, c / 1000.0, readings[static_cast<size_t>(c)]).learnt) end = c;
  }
  auto start = std::make_unique<MonitorData>(make_monitor_data(m));
  for (long c = 0; c < end; ++c) monitor_step(m, *start, c / 1000.0, readings[static_cast<size_t>(c)]);
  auto d = std::make_unique<MonitorData>();
  for (auto _ : state) {
    state.PauseTiming();
    *d = *start;
    state.ResumeTiming();
    const StepResult r = monitor_step(m, *d, end / 1000.0, readings[static_cast<size_t>(end)]);
    benchmark::DoNotOptimize(r);
    if (!r.learnt) state.SkipWithError("the timed cycle did not end the learning phase");
  }
}
BENCHMARK(BM_MonitorStepLearningEnd)->Unit(benchmark::kMicrosecond);

void BM_MonitorStepReview(benchmark::State& state) {
  MonitorSettings s;
  s.map_radius_rad = state.range(0) == 1 ? 3e-3 : 0.0;  // /1: with the configuration map
  s.cycle_hz = state.range(0) == 2 ? 250.0 : 4000.0;    // the review's work a cycle (monitor.cpp review_units)
  const MonitorModel m = make_monitor_model(s);
  static const std::vector<Eigen::Vector3d> readings = circle_readings(12000);
  auto start = std::make_unique<MonitorData>(make_monitor_data(m));
  long first = 0;
  for (; first < 12000 && start->review_stage == 0; ++first)
    monitor_step(m, *start, first / 1000.0, readings[static_cast<size_t>(first)]);
  if (start->review_stage == 0) {
    state.SkipWithError("the review did not start");
    return;
  }
  auto d = std::make_unique<MonitorData>(*start);
  long c = first;
  for (auto _ : state) {
    if (d->review_stage == 0 || c >= 12000) {
      state.PauseTiming();
      *d = *start;
      c = first;
      state.ResumeTiming();
    }
    benchmark::DoNotOptimize(monitor_step(m, *d, c / 1000.0, readings[static_cast<size_t>(c)]));
    ++c;
  }
}
BENCHMARK(BM_MonitorStepReview)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);

}  // namespace
