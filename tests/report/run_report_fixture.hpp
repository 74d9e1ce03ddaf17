// A run report of realistic size built from plain numbers (no twin, no
// solver): 3000 samples on a spiral, a cold-start LM with rejected steps,
// all three accuracy rows, long expectation details and notes. Shared by
// test_run_report.cpp and test_html_in_browser.cpp.
#pragma once

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "models/parameters.hpp"
#include "report/run_report.hpp"

namespace gpm::report::testing {

// The LM record: J starts at 1e2 and each accepted step divides it by 10
// (and the step length by 3); the steps of iterations 3 and 6 are rejected
// (J at the rejected point 4x the current J). n = 12: final J = 1e-8.
inline std::vector<RunLmIteration> lm_record(int n, std::vector<int> rejected = {3, 6}) {
  std::vector<RunLmIteration> out{{0, 1e2, 0.0, true}};
  double j = 1e2, step = 1.0;
  for (int i = 1; i <= n; ++i) {
    if (std::find(rejected.begin(), rejected.end(), i) != rejected.end()) {
      out.push_back({i, 4.0 * j, step, false});
      continue;
    }
    j *= 0.1;
    out.push_back({i, j, step, true});
    step /= 3.0;
  }
  return out;
}

inline RunReport run_report_example() {
  RunReport o;
  o.name = "example";
  o.scenario_file = "scenarios/an_example_scenario_with_a_rather_long_file_name_for_wrapping.yaml";
  o.seconds = 12.3;
  o.actual = o.nominal.geometry;
  const double dx[kNumParams] = {0, 0, 0, 0, 0.3, -0.2, 0.5, -0.4, 0.2, 0.1, -0.3, 0.25, 0.01, -0.02, 0.015};
  for (int i = 0; i < kNumParams; ++i) o.actual[i] += dx[i];
  for (int j = 0; j < 3000; ++j) {
    const double t = 0.01 * j, r = 20.0 + 0.03 * j;
    o.sample_xy.push_back(o.nominal.home + Eigen::Vector2d(r * std::cos(t), r * std::sin(t)));
  }
  for (int j = 0; j < 8; ++j) o.test_poses.push_back(o.nominal.home + Eigen::Vector2d(40.0 * std::cos(j), 40.0 * std::sin(j)));
  RunCalibration c;
  c.method = "lm";
  c.cost = "ml";
  c.geometry = o.actual;
  c.free = default_free_mask();
  c.sigma.fill(std::nan(""));
  for (int i = 0; i < kNumParams; ++i) {
    if (!c.free.test(static_cast<size_t>(i))) continue;
    const double s = is_offset(i) ? 2e-6 : 1e-3;
    c.sigma[static_cast<size_t>(i)] = s;
    o.crb[static_cast<size_t>(i)] = 0.8 * s;
    c.geometry[i] += (i % 2 ? 1.5 : -2.5) * s;
  }
  for (int i = 0; i < kNumParams; ++i)
    if (!c.free.test(static_cast<size_t>(i))) o.crb[static_cast<size_t>(i)] = std::nan("");
  c.lm_iterations = lm_record(12);
  c.final_cost = c.lm_iterations.back().cost;
  c.iterations = 12;
  c.evaluations = 25;
  c.rank = 11;
  c.condition_number = 93.1;
  c.kmrmse_mm = 0.012;
  c.notes = {"estimated with the geometry: latch skew s2 -5.53e-05 s, s3 -2.3e-05 s; transmission compliance c1 0, "
             "c2 7.31e-05, c3 0.000234 rad/N m (0: not excited, e.g. a torque-off joint)"};
  o.calibration = c;
  o.crb_sigma_rad = 1.38e-5;
  for (int j = 0; j < 3000; ++j) o.residual_urad.push_back(30.0 * std::sin(0.05 * j) + (j == 17 ? 900.0 : 0.0));
  auto accuracy = [](const std::string& label, double um) {
    RunAccuracy a;
    a.label = label;
    a.static_rms_um = um, a.static_max_um = 1.3 * um, a.path_rms_um = 1.1 * um, a.path_max_um = 1.6 * um;
    a.static_preload_rms_nm = 0.0127, a.path_preload_rms_nm = 0.578;
    for (int k = 0; k < 400; ++k) a.path_t_s.push_back(0.01 * k), a.path_error_um.push_back(um * (1.2 + std::sin(0.05 * k)));
    return a;
  };
  o.before = accuracy("nominal", 9681.94);
  o.after = accuracy("calibrated", 28.15);
  o.floor = accuracy("actual", 10.71);
  o.robot_time_s = 10.07;
  o.on_the_fly = true;
  o.model_test = RunModelTest{2.844e5, 10058, 0.0, 1.38e-5, false,
                              "residuals are 5.32x the encoder noise throughout: an unmodelled effect"};
  o.checks = {{"floor_ratio", "static RMS 28.150 um calibrated, 10.714 um with the actual parameters: x2.63 (limit x3.5)", true},
              {"improvement", "static RMS 9681.942 -> 28.150 um, x344 (at least x200)", true},
              {"residual", "largest residual 900 urad at sample 17, a reading that jumped; the detail goes on to make "
                           "the cell long enough to wrap over several lines in a narrow window",
               false}};
  return o;
}

}  // namespace gpm::report::testing
