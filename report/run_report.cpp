#include "report/run_report.hpp"

#include <cmath>

#include <fmt/format.h>

#include "models/kinematics.hpp"
#include "report/svg_plot.hpp"

namespace gpm::report {
namespace {

std::string num(double v, int digits = 6) {
  if (std::isnan(v)) return "-";
  return fmt::format("{:.{}g}", v, digits);
}

std::string unit(int i) { return is_offset(i) ? "rad" : "mm"; }

std::string layout_figure(const RunReport& o) {
  Series reach;
  reach.label = "reachable with margins";
  reach.style = Series::Style::kMarkers;
  reach.color = "#e4e4e4";
  for (double x = -60; x <= 500; x += 12)
    for (double y = -60; y <= 560; y += 12)
      if (check_reach(o.nominal, {x, y}).ok) reach.x.push_back(x), reach.y.push_back(y);
  Series samples;
  samples.label = "calibration samples";
  samples.style = Series::Style::kMarkers;
  for (const auto& p : o.sample_xy) samples.x.push_back(p.x()), samples.y.push_back(p.y());
  Series bases;
  bases.label = "base joints A1..A3";
  bases.style = Series::Style::kMarkers;
  bases.color = "#000000";
  for (int i = 0; i < 3; ++i) bases.x.push_back(o.nominal.geometry.A(i).x()), bases.y.push_back(o.nominal.geometry.A(i).y());
  std::vector<Series> all{reach, samples, bases};
  if (!o.test_poses.empty()) {
    Series test;
    test.label = "accuracy test poses";
    test.style = Series::Style::kMarkers;
    test.color = "#2ca02c";
    for (const auto& p : o.test_poses) test.x.push_back(p.x()), test.y.push_back(p.y());
    all.push_back(test);
  }
  PlotOptions po;
  po.title = "Sample layout over the workspace";
  po.x_label = "x (mm)";
  po.y_label = "y (mm)";
  po.equal_aspect = true;
  po.height = 520;
  return svg_plot(all, po);
}

std::string residual_figure(const RunReport& o) {
  Series r;
  r.label = "ML residual after calibration (urad)";
  r.style = Series::Style::kMarkers;
  for (size_t j = 0; j < o.residual_urad.size(); ++j) r.x.push_back(static_cast<double>(j)), r.y.push_back(o.residual_urad[j]);
  PlotOptions po;
  po.title = "Closure residual per sample (reading-space, maximum-likelihood scaling)";
  po.x_label = "sample";
  po.y_label = "urad";
  return svg_plot({r}, po);
}

std::string convergence_figure(const RunCalibration& r) {
  Series s;
  s.label = fmt::format("{} on {}", r.method, r.cost);
  s.style = Series::Style::kLineMarkers;
  for (const auto& [e, j] : r.history) s.x.push_back(static_cast<double>(e)), s.y.push_back(j);
  PlotOptions po;
  po.title = "Convergence";
  po.x_label = "error-function evaluations";
  po.y_label = "cost J";
  po.log_y = true;
  return svg_plot({s}, po);
}

std::string error_figure(const RunReport& o, bool offsets) {
  const RunCalibration& r = *o.calibration;
  Series err;
  err.label = offsets ? "estimate - actual (mrad), bars: 1-sigma" : "estimate - actual (mm), bars: 1-sigma";
  err.style = Series::Style::kMarkers;
  Series bound;
  bound.label = "Cramer-Rao bound (1-sigma)";
  bound.style = Series::Style::kMarkers;
  bound.color = "#bbbbbb";
  PlotOptions po;
  po.title = offsets ? "Encoder zero-offset errors" : "Base and link errors";
  po.y_label = offsets ? "mrad" : "mm";
  const double k = offsets ? 1e3 : 1.0;
  for (int i = 0; i < kNumParams; ++i) {
    if (!r.free.test(static_cast<size_t>(i)) || is_offset(i) != offsets) continue;
    const double x = static_cast<double>(po.x_categories.size());
    po.x_categories.emplace_back(param_name(i));
    err.x.push_back(x);
    err.y.push_back(k * (r.geometry[i] - o.actual[i]));
    err.y_err.push_back(std::isnan(r.sigma[static_cast<size_t>(i)]) ? 0.0 : k * r.sigma[static_cast<size_t>(i)]);
    if (std::isfinite(o.crb[static_cast<size_t>(i)])) {
      bound.x.push_back(x);
      bound.y.push_back(k * o.crb[static_cast<size_t>(i)]);
    }
  }
  return svg_plot({err, bound}, po);
}

std::string tracking_figure(const RunReport& o) {
  std::vector<Series> all;
  for (const RunAccuracy* a : {o.before ? &*o.before : nullptr, o.after ? &*o.after : nullptr}) {
    if (!a) continue;
    Series s;
    s.label = fmt::format("{} model", a->label);
    s.x = a->path_t_s;
    s.y = a->path_error_um;
    all.push_back(s);
  }
  PlotOptions po;
  po.title = "Tracking error along the test path";
  po.x_label = "t (s)";
  po.y_label = "|actual - desired| (um)";
  po.log_y = true;
  return svg_plot(all, po);
}

}  // namespace

ReportDocument build_run_report(const RunReport& o) {
  ReportDocument d;
  d.heading(1, fmt::format("gpm run: {}", o.name));
  std::vector<std::string> failed;
  for (const RunCheck& c : o.checks)
    if (!c.passed) failed.push_back(fmt::format("{}: {}", c.name, c.detail));
  d.paragraph(fmt::format("Scenario {}. Verdict: {} ({} expectations checked, {} failed). Run time {:.1f} s.",
                          o.scenario_file, failed.empty() ? "PASSED" : "FAILED", o.checks.size(),
                          failed.size(), o.seconds));
  if (!failed.empty()) d.bullets(failed);
  if (!o.hardware_description.empty()) {
    d.paragraph(fmt::format("Samples taken through the hardware interface ({}). Errors are against the scenario's "
                            "actual robot, the truth when that hardware simulates this scenario.",
                            o.hardware_description));
  }

  if (o.before) {
    d.heading(2, "Accuracy before and after calibration");
    d.paragraph("The twin (actual parameters) driven by the controller's model: static error after settling at the "
                "test poses, tracking error along the test path, and the servos' internal preload |P tau| (torques "
                "that do no work on the end-effector, eq. 15).");
    std::vector<std::vector<std::string>> rows;
    for (const RunAccuracy* a : {&*o.before, o.after ? &*o.after : nullptr, o.floor ? &*o.floor : nullptr}) {
      if (!a) continue;
      rows.push_back({a->label, fmt::format("{:.2f}", a->static_rms_um), fmt::format("{:.2f}", a->static_max_um),
                      fmt::format("{:.2f}", a->path_rms_um), fmt::format("{:.2f}", a->path_max_um),
                      fmt::format("{:.4f}", a->static_preload_rms_nm), fmt::format("{:.4f}", a->path_preload_rms_nm)});
    }
    d.table({"controller model", "static RMS (um)", "static max (um)", "path RMS (um)", "path max (um)",
             "static preload RMS (N m)", "path preload RMS (N m)"},
            rows);
    if (o.after) {
      d.paragraph(fmt::format("Static accuracy improved x{:.3g}; path tracking x{:.3g}; preload x{:.3g}.",
                              o.before->static_rms_um / o.after->static_rms_um,
                              o.before->path_rms_um / o.after->path_rms_um,
                              o.before->static_preload_rms_nm / std::max(1e-12, o.after->static_preload_rms_nm)));
    }
    if (o.after && o.floor) {
      d.paragraph(fmt::format("The `actual` row is the floor: the controller given the true parameters. Calibrated "
                              "static RMS is {:.2f}x the floor. Sampling took {:.2f} s of robot time.",
                              o.after->static_rms_um / std::max(1e-12, o.floor->static_rms_um), o.robot_time_s));
    }
  }
  if (o.model_test) {
    const RunModelTest& t = *o.model_test;
    d.paragraph(fmt::format("Model test: chi2 = {:.4g} for {:.0f} degrees of freedom (encoder sigma {:.3g} rad), "
                            "p = {:.3g}: {}.",
                            t.chi2, t.dof, t.sigma_rad, t.p_value,
                            t.passed ? "the residuals are as small as the encoders explain" : t.diagnosis));
  }

  d.heading(2, "Calibration");
  if (o.refused) {
    d.paragraph("The calibration was refused, as the scenario expects:");
    d.preformatted(*o.refused);
  }
  if (o.calibration) {
    const RunCalibration& r = *o.calibration;
    d.paragraph(fmt::format("{} on {} from {} encoder samples, {} free parameters (fixed: {}). Bound at encoder "
                            "sigma {:.3g} rad per sample.",
                            r.method, r.cost, o.sample_xy.size(), r.free.count(),
                            format_param_list(~r.free), o.crb_sigma_rad));
    std::vector<std::vector<std::string>> rows;
    for (int i = 0; i < kNumParams; ++i) {
      const bool free = r.free.test(static_cast<size_t>(i));
      const double err = r.geometry[i] - o.actual[i];
      rows.push_back({std::string(param_name(i)) + " (" + unit(i) + ")", num(o.nominal.geometry[i], 8),
                      num(o.actual[i], 10), num(r.geometry[i], 10),
                      free ? num(r.sigma[static_cast<size_t>(i)], 3) : "fixed", free ? num(err, 3) : "-",
                      free ? num(o.crb[static_cast<size_t>(i)], 3) : "-",
                      free ? num(std::abs(err) / o.crb[static_cast<size_t>(i)], 3) : "-"});
    }
    d.table({"parameter", "nominal", "actual", "estimated", "1-sigma", "error", "CRB sigma", "|error|/CRB"}, rows);
    d.heading(3, "Diagnostics");
    d.table({"cost J", "iterations", "evaluations", "rank", "condition number", "kmrmse (mm)", "seconds", "converged"},
            {{num(r.final_cost, 4), std::to_string(r.iterations), std::to_string(r.evaluations),
              std::to_string(r.rank), num(r.condition_number, 4), r.kmrmse_mm ? num(*r.kmrmse_mm, 4) : "-",
              num(r.seconds, 3), r.converged ? "yes" : "no"}});
    if (!r.notes.empty()) d.bullets(r.notes);
  }

  if (!o.checks.empty()) {
    d.heading(2, "Expectations");
    std::vector<std::vector<std::string>> rows;
    for (const RunCheck& c : o.checks) rows.push_back({c.name, c.passed ? "pass" : "FAIL", c.detail});
    d.table({"check", "result", "measured"}, rows);
  }

  d.heading(2, "Figures");
  d.figure("layout", "Calibration samples and accuracy test poses over the reachable workspace", layout_figure(o));
  if (o.calibration) {
    d.figure("residuals", "Closure residual of each sample after calibration", residual_figure(o));
    if (!o.calibration->history.empty()) d.figure("convergence", "Cost against evaluations", convergence_figure(*o.calibration));
    d.figure("errors_mm", "Base and link errors with 1-sigma and the Cramer-Rao bound", error_figure(o, false));
    d.figure("errors_offsets", "Offset errors with 1-sigma and the Cramer-Rao bound", error_figure(o, true));
  }
  if (o.before) d.figure("tracking", "Tracking error along the test path, nominal and calibrated model", tracking_figure(o));
  return d;
}

}  // namespace gpm::report
