#include "run/run_report_data.hpp"

#include "calib/problem.hpp"
#include "run/runner.hpp"

namespace gpm::scenario {
namespace {

report::RunAccuracy accuracy_data(const Accuracy& a) {
  report::RunAccuracy r;
  r.label = a.label;
  r.static_rms_um = a.static_rms_um;
  r.static_max_um = a.static_max_um;
  r.path_rms_um = a.path_rms_um;
  r.path_max_um = a.path_max_um;
  r.static_preload_rms_nm = a.static_preload_rms_nm;
  r.path_preload_rms_nm = a.path_preload_rms_nm;
  const double t0 = a.path_log.rows.empty() ? 0.0 : a.path_log.rows.front().t;
  for (size_t k = 0; k < a.path_log.rows.size(); k += 10) {
    const auto& row = a.path_log.rows[k];
    r.path_t_s.push_back(row.t - t0);
    r.path_error_um.push_back((row.actual - row.desired).norm() * 1e3);
  }
  return r;
}

report::RunCalibration calibration_data(const calib::Result& c) {
  report::RunCalibration r;
  r.method = c.method;
  r.cost = std::string(calib::cost_name(c.cost));
  r.geometry = c.geometry;
  r.free = c.free;
  r.sigma = c.sigma;
  r.final_cost = c.final_cost;
  r.iterations = c.iterations;
  r.evaluations = c.evaluations;
  r.rank = c.rank;
  r.condition_number = c.condition_number;
  r.kmrmse_mm = c.kmrmse_mm;
  r.seconds = c.seconds;
  r.converged = c.converged;
  r.notes = c.notes;
  r.history = c.history;
  for (const calib::LmIteration& it : c.lm_iterations)
    r.lm_iterations.push_back({it.iteration, it.cost, it.step_norm, it.accepted});
  return r;
}

}  // namespace

report::RunReport run_report_data(const RunOutcome& o) {
  report::RunReport r;
  r.name = o.spec.sim.name;
  r.scenario_file = o.scenario_file;
  r.hardware_description = o.hardware_description;
  r.seconds = o.seconds;
  r.nominal = o.nominal;
  r.actual = o.sim.actual.geometry;
  for (const auto& s : o.sim.samples) r.sample_xy.push_back(s.xy_mm);
  if (o.spec.compensation) r.test_poses = o.spec.compensation->poses;
  r.refused = o.refused;
  if (o.calibration) r.calibration = calibration_data(*o.calibration);
  r.crb_sigma_rad = o.crb_sigma_rad;
  r.crb = o.crb;
  r.residual_urad = o.residual_urad;
  if (o.before) r.before = accuracy_data(*o.before);
  if (o.after) r.after = accuracy_data(*o.after);
  if (o.floor) r.floor = accuracy_data(*o.floor);
  r.floor_ratio_ci95 = o.floor_ratio_ci95;
  if (o.model_test)
    r.model_test = report::RunModelTest{o.model_test->chi2, o.model_test->dof, o.model_test->p_value,
                                        o.model_test->sigma_rad, o.model_test->passed, o.model_test->diagnosis,
                                        o.model_test->doubt_chi2};
  r.robot_time_s = o.sim.sampling_s;
  r.on_the_fly = o.in_motion;
  if (o.positioning)
    r.positioning_um = std::array<double, 5>{o.positioning->rms_um, o.positioning->max_um,
                                             o.positioning->stated_sigma_rms_um, o.positioning->normalised_rms,
                                             o.positioning->carried_sigma_rms_um};
  if (o.positioning)
    for (const calib::PositioningPoint& m : o.positioning->map)
      r.positioning_map.push_back({m.p, m.error * 1e3, m.sigma_um});
  if (o.stated_positioning) {
    r.stated_positioning_um = std::array<double, 2>{o.stated_positioning->stated_sigma_rms_um,
                                                    o.stated_positioning->carried_sigma_rms_um};
    for (const calib::PositioningPoint& m : o.stated_positioning->map)
      r.positioning_map.push_back({m.p, Eigen::Vector2d::Zero(), m.sigma_um});
  }
  r.positioning_bound_um = o.positioning_bound_um;
  for (const Check& c : o.checks) r.checks.push_back({c.name, c.detail, c.passed});
  return r;
}

}  // namespace gpm::scenario
