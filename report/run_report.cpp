#include "report/run_report.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <regex>

#include <fmt/format.h>

#include "models/kinematics.hpp"
#include "report/svg_plot.hpp"
#include "report/table_cell.hpp"

namespace gpm::report {
namespace {

std::string num(double v, int digits = 6) {
  if (std::isnan(v)) return "-";
  return fmt::format("{:.{}g}", v, digits);
}

std::string unit(int i) { return is_offset(i) ? "rad" : "mm"; }

// Text from the run library reads as a reader reads it (readable_text,
// report/report_document.hpp): "28.15 um" as "28.15 µm", "7.31e-05" as
// "7.31×10⁻⁵", "x2.63" as "×2.63".
std::string with_unit_symbols(const std::string& text) { return readable_text(text); }

// A distance in µm as a reader says it: mm from 1000 µm on, 3 significant digits.
// (Number and unit joined by a no-break space: a line never starts with the unit.)
std::string distance(double um) {
  return std::abs(um) >= 1000.0 ? sig(um / 1000.0) + "\u00a0mm" : sig(um) + "\u00a0µm";
}

// The calibration method and cost in words ("lm on ml" is for the terminal).
std::string method_words(const std::string& method, const std::string& cost) {
  const std::string m = method == "lm"      ? "Levenberg-Marquardt"
                        : method == "de"    ? "differential evolution"
                        : method == "ga"    ? "a genetic algorithm"
                        : method == "pso"   ? "particle swarm optimisation"
                        : method == "de+lm" ? "differential evolution, then Levenberg-Marquardt"
                                            : method;
  std::string c = cost;
  for (char& ch : c) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  return m + (cost == "ml" ? " on the maximum-likelihood residual" : " on the paper's cost " + c);
}

// At most about `limit` points of a long series are drawn: every k-th.
size_t thinning(size_t n, size_t limit) { return n <= limit ? 1 : (n + limit - 1) / limit; }

std::string layout_figure(const RunReport& o) {
  Series reach;
  reach.label = "reachable with margins";
  reach.style = Series::Style::kMarkers;
  reach.color = "#e4e4e4";
  for (double x = -60; x <= 500; x += 12)
    for (double y = -60; y <= 560; y += 12)
      if (check_reach(o.nominal, {x, y}).ok) reach.x.push_back(x), reach.y.push_back(y);
  Series samples;
  const size_t k = thinning(o.sample_xy.size(), 1500);
  samples.label = k == 1 ? fmt::format("calibration samples ({})", o.sample_xy.size())
                         : fmt::format("calibration samples (1 in {} of {} drawn)", k, o.sample_xy.size());
  samples.style = Series::Style::kMarkers;
  samples.marker_size = k == 1 ? 3.0 : 2.0;
  for (size_t j = 0; j < o.sample_xy.size(); j += k) samples.x.push_back(o.sample_xy[j].x()), samples.y.push_back(o.sample_xy[j].y());
  Series bases;
  bases.label = "base joints A1, A2, A3 (nominal)";
  bases.style = Series::Style::kMarkers;
  bases.marker = Series::Marker::kTriangle;
  bases.marker_size = 5;
  bases.color = "#000000";
  for (int i = 0; i < 3; ++i) {
    bases.x.push_back(o.nominal.geometry.A(i).x());
    bases.y.push_back(o.nominal.geometry.A(i).y());
    bases.point_labels.push_back(fmt::format("A{}", i + 1));
  }
  Series home;
  home.label = fmt::format("home ({:.1f}, {:.1f})", o.nominal.home.x(), o.nominal.home.y());
  home.style = Series::Style::kMarkers;
  home.marker = Series::Marker::kCross;
  home.marker_size = 6;
  home.color = "#9467bd";
  home.x = {o.nominal.home.x()};
  home.y = {o.nominal.home.y()};
  home.point_labels = {"home"};
  std::vector<Series> all{reach, samples, bases, home};
  if (!o.test_poses.empty()) {
    Series test;
    test.label = "accuracy test poses";
    test.style = Series::Style::kMarkers;
    test.marker_size = 4;
    test.color = "#2ca02c";
    for (const auto& p : o.test_poses) test.x.push_back(p.x()), test.y.push_back(p.y());
    all.push_back(test);
  }
  PlotOptions po = workspace_plot("Sample layout over the workspace");
  po.height = 520;
  return svg_plot(all, po);
}

std::string residual_figure(const RunReport& o) {
  // Long runs: the smallest and the largest residual of each run of k
  // samples, so no outlier disappears.
  const size_t n = o.residual_urad.size(), k = thinning(n, 1000);
  Series r;
  r.label = k == 1 ? "ML residual after calibration (µrad)"
                   : fmt::format("ML residual after calibration (µrad), extremes of every {} samples", k);
  r.style = Series::Style::kMarkers;
  r.marker_size = 2;
  for (size_t j = 0; j < n; j += k) {
    size_t lo = j, hi = j;
    for (size_t i = j; i < std::min(n, j + k); ++i) {
      if (o.residual_urad[i] < o.residual_urad[lo]) lo = i;
      if (o.residual_urad[i] > o.residual_urad[hi]) hi = i;
    }
    for (size_t i : {std::min(lo, hi), std::max(lo, hi)}) {
      r.x.push_back(static_cast<double>(i));
      r.y.push_back(o.residual_urad[i]);
      if (lo == hi) break;
    }
  }
  return svg_plot({r}, titled_plot("Closure residual per sample (reading space, maximum-likelihood scaling)",
                                    "sample", "residual (µrad)"));
}

// The LM record counted as the terminal counts it: passes (each starts
// with an entry that tried no step), the steps tried in all and those of
// the last pass (the terminal's "iterations").
struct LmCount {
  int passes = 0, steps = 0, last_pass_steps = 0;
};
LmCount lm_count(const RunCalibration& r) {
  LmCount c;
  for (const RunLmIteration& it : r.lm_iterations) {
    if (!(it.step_norm > 0.0)) {
      ++c.passes;
      c.last_pass_steps = 0;
    } else {
      ++c.steps;
      ++c.last_pass_steps;
    }
  }
  return c;
}

// "7 iterations", or "38 iterations in 5 passes (7 in the last)": the
// terminal's count is the last pass's.
std::string lm_count_text(const RunCalibration& r) {
  const LmCount c = lm_count(r);
  if (c.passes <= 1) return fmt::format("{} iteration{}", r.iterations, r.iterations == 1 ? "" : "s");
  return fmt::format("{} iterations in {} passes ({} in the last)", c.steps, c.passes, r.iterations);
}

// Two panels over the LM iterations: J, and the length of each step tried.
// J spanning more than a decade is drawn on a log axis; a warm start that
// changes J by a small fraction as J - J_final on a linear axis, so the
// changes stay readable.
std::string lm_convergence_figure(const RunCalibration& r) {
  double j_min = std::numeric_limits<double>::infinity(), j_max = 0.0;
  for (const RunLmIteration& it : r.lm_iterations)
    if (std::isfinite(it.cost)) j_min = std::min(j_min, it.cost), j_max = std::max(j_max, it.cost);
  const bool log_j = j_min > 0.0 && j_max > 10.0 * j_min;
  const double j_ref = log_j || !std::isfinite(j_min) ? 0.0 : r.final_cost;
  Series cost, cost_rejected, step, step_rejected;
  cost.label = "cost J after each iteration";
  cost.style = Series::Style::kLineMarkers;
  step.label = "step accepted";
  step.style = Series::Style::kLineMarkers;
  cost_rejected.label = step_rejected.label = "step rejected (J at the point rejected)";
  cost_rejected.style = step_rejected.style = Series::Style::kMarkers;
  cost_rejected.marker = step_rejected.marker = Series::Marker::kCross;
  cost_rejected.color = step_rejected.color = "#d62728";
  for (const RunLmIteration& it : r.lm_iterations) {
    const double x = it.iteration;
    (it.accepted ? cost : cost_rejected).x.push_back(x);
    (it.accepted ? cost : cost_rejected).y.push_back(it.cost - j_ref);
    if (it.iteration == 0 || !(it.step_norm > 0.0)) continue;  // no step at a start (or a pass's restart)
    (it.accepted ? step : step_rejected).x.push_back(x);
    (it.accepted ? step : step_rejected).y.push_back(it.step_norm);
  }
  PlotOptions pc;
  pc.title = "Levenberg-Marquardt: " + lm_count_text(r);
  pc.x_label = "iteration";
  pc.y_label = log_j ? "cost J" : "J − final J";
  pc.log_y = log_j;
  pc.integer_x = true;
  pc.height = 300;
  PlotOptions ps = pc;
  ps.title.clear();
  ps.y_label = "step length |Δx|";
  ps.log_y = true;
  // Both panels span the same iterations so they line up: an invisible
  // point at each end of the axis.
  const double last = r.lm_iterations.empty() ? 1.0 : r.lm_iterations.back().iteration;
  Series cost_span, step_span;
  cost_span.style = step_span.style = Series::Style::kMarkers;
  cost_span.marker_size = step_span.marker_size = 0;
  cost_span.x = step_span.x = {0.0, last};
  const double c0 = cost.y.empty() ? 1.0 : cost.y.front(), s0 = step.y.empty() ? 1.0 : step.y.front();
  cost_span.y = {c0, c0};
  step_span.y = {s0, s0};
  std::vector<Series> top{cost}, bottom{step};
  if (!cost_rejected.x.empty()) top.push_back(cost_rejected);
  if (!step_rejected.x.empty()) bottom.push_back(step_rejected);
  top.push_back(cost_span);
  bottom.push_back(step_span);
  return svg_stack({svg_plot(top, pc), svg_plot(bottom, ps)});
}

// The global methods' record: best J against error-function evaluations.
std::string history_figure(const RunCalibration& r) {
  Series s;
  s.label = method_words(r.method, r.cost);
  s.style = Series::Style::kLineMarkers;
  for (const auto& [e, j] : r.history) s.x.push_back(static_cast<double>(e)), s.y.push_back(j);
  PlotOptions po = titled_plot("Convergence", "error-function evaluations", "best cost J");
  po.log_y = true;
  return svg_plot({s}, po);
}

std::string error_figure(const RunReport& o, bool offsets) {
  const RunCalibration& r = *o.calibration;
  Series err;
  err.label = "estimate − actual, bars: the calibration's 1σ";
  err.style = Series::Style::kMarkers;
  Series bound1, bound3;
  bound1.label = "Cramér-Rao bound: ±1σ band";
  bound3.label = "±3σ band";
  bound1.style = bound3.style = Series::Style::kBand;
  bound1.color = bound3.color = "#7f7f7f";
  bound1.opacity = 0.45;
  bound3.opacity = 0.18;
  PlotOptions po;
  po.title = offsets ? "Encoder zero-offset errors" : "Base and link errors";
  po.y_label = offsets ? "error (µrad)" : "error (µm)";
  const double scale = offsets ? 1e6 : 1e3;  // rad -> µrad, mm -> µm
  for (int i = 0; i < kNumParams; ++i) {
    if (!r.free.test(static_cast<size_t>(i)) || is_offset(i) != offsets) continue;
    const double x = static_cast<double>(po.x_categories.size());
    po.x_categories.emplace_back(param_name(i));
    err.x.push_back(x);
    err.y.push_back(scale * (r.geometry[i] - o.actual[i]));
    err.y_err.push_back(std::isnan(r.sigma[static_cast<size_t>(i)]) ? 0.0 : scale * r.sigma[static_cast<size_t>(i)]);
    const double crb = o.crb[static_cast<size_t>(i)];
    if (std::isfinite(crb)) {
      for (Series* b : {&bound1, &bound3}) b->x.push_back(x), b->y.push_back(0.0);
      bound1.y_err.push_back(scale * crb);
      bound3.y_err.push_back(3.0 * scale * crb);
    }
  }
  return svg_plot({err, bound1, bound3}, po);
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
  PlotOptions po = titled_plot("Tracking error along the test path", "t (s)", "|actual − desired| (µm)");
  po.log_y = true;
  return svg_plot(all, po);
}

// The worst parameter error in Cramér-Rao sigmas (NaN: none known).
double worst_crb_ratio(const RunReport& o) {
  double worst = std::numeric_limits<double>::quiet_NaN();
  if (!o.calibration) return worst;
  for (int i = 0; i < kNumParams; ++i) {
    const double crb = o.crb[static_cast<size_t>(i)];
    if (!o.calibration->free.test(static_cast<size_t>(i)) || !(crb > 0.0)) continue;
    const double k = std::abs(o.calibration->geometry[i] - o.actual[i]) / crb;
    if (!(k <= worst)) worst = k;
  }
  return worst;
}

// The lead: how far the tool tip stood from where it was sent, before and
// after, in one sentence a manager reads (or why there is no after).
std::string lead_sentence(const RunReport& o) {
  // How long the sampling kept the robot from its work: what a user plans for.
  const std::string readings =
      o.hardware_description.empty() && o.robot_time_s > 0.0
          ? fmt::format("{} of its own encoder readings, taken {} in {} s of robot time (all the time the "
                        "calibration keeps the robot from its work)",
                        o.sample_xy.size(), o.on_the_fly ? "on the fly" : "at rest at each pose", sig(o.robot_time_s, 2))
          : fmt::format("{} samples of its own encoder readings", o.sample_xy.size());
  if (o.refused) return "The calibration was refused (see Calibration below); the robot keeps its nominal model.";
  if (o.before && o.after) {
    std::string s = fmt::format(
        "With its nominal model the robot's tool tip stood {} from where it was sent (RMS over {} test poses); "
        "calibrated from {}, it stands {} away: {}× closer",
        distance(o.before->static_rms_um), o.test_poses.empty() ? std::string("the") : std::to_string(o.test_poses.size()),
        readings, distance(o.after->static_rms_um), ratio_text(o.before->static_rms_um / o.after->static_rms_um));
    if (o.floor)
      s += fmt::format(", and {}× the error of a controller that knew the true parameters and reading errors ({})",
                       ratio_text(o.after->static_rms_um / o.floor->static_rms_um), distance(o.floor->static_rms_um));
    return s + ".";
  }
  if (o.calibration && o.positioning_um)
    return fmt::format("Calibrated from {}, the model places the tool tip within {} (RMS over an 80 mm disc round "
                       "home) of where it is sent.",
                       readings, distance((*o.positioning_um)[0]));
  if (o.calibration) {
    const double k = worst_crb_ratio(o);
    return fmt::format("Calibrated from {}{}.", readings,
                       std::isfinite(k) ? fmt::format(": every parameter within {} Cramér-Rao σ of its true value",
                                                      sig(k, 2))
                                        : std::string());
  }
  return "No calibration in this run.";
}

// The model test in the verdict's voice: passed; or failed, and whether the
// stated 1-sigma covers it (the positioning error against it) and the
// scenario expects it.
std::string model_test_sentence(const RunReport& o, const RunModelTest& t) {
  const std::string doubt = t.doubt_chi2 > 0.0 ? fmt::format("; {} expected with the doubt where a joint may rest",
                                                            sig((t.dof + t.doubt_chi2) / t.dof, 3))
                                              : "";
  const std::string numbers = fmt::format("χ²/dof {}{}, p {}", sig(t.chi2 / t.dof, 3), doubt,
                                          t.p_value < 1e-3 ? "< 0.001" : "= " + sig(t.p_value, 2));
  if (t.passed)
    return fmt::format("Model test passed: the readings scatter no more than the encoders' noise {} ({}).",
                       t.doubt_chi2 > 0.0 ? "and the friction's doubt explain" : "explains", numbers);
  bool expected = false;
  for (const RunCheck& c : o.checks) expected = expected || (c.name == "model_test" && c.passed);
  const ModelTestVerdict v = model_test_verdict(
      t.passed, t.chi2, t.dof, o.positioning_um ? std::optional<double>((*o.positioning_um)[3]) : std::nullopt);
  std::string s = fmt::format("Model test: the readings scatter {}× the encoders' noise ({}), more than noise alone "
                              "explains, so the model leaves some effect out{}.",
                              sig(v.scatter, 3), numbers, expected ? ", as this scenario expects" : "");
  if (v.covered)
    return s + fmt::format(" The stated 1σ accounts for it: the calibrated model's positioning error is {}× its stated "
                           "1σ (1 is honest), so the result stands as stated.",
                           sig(*v.positioning, 2));
  if (v.positioning)
    s += fmt::format(" The stated 1σ understates the error: the positioning error is {}× it.", sig(*v.positioning, 2));
  // The diagnosis without its own chi-square numbers ("model test failed (...): cause").
  const size_t cause = t.diagnosis.find("): ");
  return s + " Likely cause: " +
         with_unit_symbols(cause == std::string::npos ? t.diagnosis : t.diagnosis.substr(cause + 3)) + ".";
}

}  // namespace

ModelTestVerdict model_test_verdict(bool passed, double chi2, double dof, std::optional<double> normalised_rms) {
  ModelTestVerdict v;
  v.passed = passed;
  v.scatter = dof > 0.0 ? std::sqrt(chi2 / dof) : std::numeric_limits<double>::quiet_NaN();
  v.positioning = normalised_rms;
  v.covered = !passed && normalised_rms && *normalised_rms <= kStatedSigmaCovers;
  return v;
}

std::string model_test_verdict_line(const ModelTestVerdict& v) {
  if (v.passed) return "the residuals are as small as the encoders explain";
  const std::string scatter = fmt::format("the readings scatter {}x the encoders' 1-sigma", sig(v.scatter, 2));
  if (v.covered)
    return fmt::format("{}; the stated 1-sigma accounts for it (positioning error {}x the stated 1-sigma)", scatter,
                       sig(*v.positioning, 2));
  if (v.positioning)
    return fmt::format("{}; the stated 1-sigma understates the error (positioning error {}x it; see the report's "
                       "notes for the likely cause)",
                       scatter, sig(*v.positioning, 2));
  return scatter + ", more than noise explains (see the report's notes for the likely cause)";
}

namespace {

// The title, the lead sentence, the verdict with the model test, the failed
// expectations and where the samples came from.
void add_verdict(ReportDocument& d, const RunReport& o) {
  d.heading(1, fmt::format("gpm run: {}", o.name));
  d.lead(lead_sentence(o));
  std::vector<std::string> failed;
  for (const RunCheck& c : o.checks)
    if (!c.passed) failed.push_back(fmt::format("{}: {}", c.name, with_unit_symbols(c.detail)));
  std::string verdict =
      o.checks.empty()      ? "Verdict: no expectations stated."
      : failed.empty()      ? fmt::format("Verdict: passed: {} of the scenario held.",
                                          o.checks.size() == 1   ? std::string("its one expectation")
                                          : o.checks.size() == 2 ? std::string("both expectations")
                                                                 : fmt::format("all {} expectations", o.checks.size()))
                            : fmt::format("Verdict: FAILED: {} of {} expectations did not hold (below).", failed.size(),
                                          o.checks.size());
  if (o.model_test) verdict += " " + model_test_sentence(o, *o.model_test);
  d.paragraph(verdict);
  if (!failed.empty()) d.bullets(failed);
  d.paragraph(fmt::format("Scenario `{}`, run in {} s.", o.scenario_file, sig(o.seconds, 3)));
  if (!o.hardware_description.empty()) {
    d.paragraph(fmt::format("Samples taken through the hardware interface ({}). Errors are against the scenario's "
                            "actual robot, the truth when that hardware simulates this scenario.",
                            o.hardware_description));
  }
}

// The carried share of the stated 1-sigma in a sentence ending in `ending`
// and a full stop (empty when nothing is carried).
std::string carried_sentence(double carried_um, const std::string& ending) {
  if (!(carried_um > 0.0)) return {};
  return fmt::format(" Of that 1σ, {} (in quadrature) is the error once per joint revolution carried at the data "
                     "sheet's amplitude, which the readings cannot tell from the geometry{}.",
                     distance(carried_um), ending);
}

// A positioning section: heading, paragraph, and the map when there is one (svg not empty).
void positioning_section(ReportDocument& d, const std::string& heading, const std::string& text,
                         const std::string& caption, const std::string& svg) {
  d.heading(2, heading);
  d.paragraph(text);
  if (!svg.empty()) d.figure("positioning", caption, svg);
}

// The calibrated model's positioning error over the workspace, and its map when measured.
void add_positioning(ReportDocument& d, const std::array<double, 5>& p, const std::optional<double>& bound,
                     const std::vector<RunPositioningPoint>& map) {
  const std::string text =
      fmt::format(
          "Over a disc of 80 mm round home (points 10 mm apart), the readings the calibrated model commands and "
          "where the actual robot stands when its three drives hold them, noise-free: RMS {}, max {}. The "
          "calibration's covariance states {} per axis (RMS over the points); error / stated 1σ {} (1 when the 1σ "
          "is honest).{}",
          distance(p[0]), distance(p[1]), distance(p[2]), sig(p[3], 2),
          carried_sentence(p[4], ": the floor of this procedure with these encoders")) +
      (bound ? fmt::format(" These readings allow an RMS of {} at best: the Cramér-Rao bound at the actual robot of "
                           "the calibration's reading model with {} estimated under its prior.",
                           distance(*bound),
                           p[4] > 0.0 ? "that carried error" : "the error once per joint revolution")
             : std::string());
  positioning_section(d, "Positioning error of the calibrated model", text,
                      "Where the actual robot stands, noise-free, when the calibrated model commands each point of "
                      "the disc: points coloured by the size of the error, the error drawn as an arrow",
                      map.empty() ? std::string() : positioning_map_svg(map));
}

// Through hardware: the positioning 1-sigma the calibration states (s[0] per
// axis, s[1] its carried share), and its map.
void add_stated_positioning(ReportDocument& d, const std::array<double, 2>& s,
                            const std::vector<RunPositioningPoint>& map) {
  positioning_section(
      d, "Positioning 1σ of the calibrated model",
      fmt::format("Over a disc of 80 mm round home (points 10 mm apart), the calibration's covariance states a "
                  "positioning 1σ of {} per axis (RMS over the points), by the calibrated model's own "
                  "sensitivities.{} The error itself needs the actual robot, known in simulation only.",
                  distance(s[0]), carried_sentence(s[1], "")),
      "The stated positioning 1σ per axis at each point of the disc",
      map.empty() ? std::string() : stated_sigma_map_svg(map));
}

// The accuracy table of the nominal, calibrated and actual controller models and their ratios.
void add_accuracy(ReportDocument& d, const RunReport& o) {
  d.heading(2, "Accuracy before and after calibration");
  d.paragraph("The twin (actual parameters) driven by the controller's model: static error after settling at the "
              "test poses, tracking error along the test path, and the servos' internal preload |P τ| (torques "
              "that do no work on the end-effector, eq. 15).");
  std::vector<std::vector<std::string>> rows;
  for (const RunAccuracy* a : {&*o.before, o.after ? &*o.after : nullptr, o.floor ? &*o.floor : nullptr}) {
    if (!a) continue;
    rows.push_back({a->label, sig(a->static_rms_um), sig(a->static_max_um), sig(a->path_rms_um),
                    sig(a->path_max_um), sig(a->static_preload_rms_nm), sig(a->path_preload_rms_nm)});
  }
  d.table({"controller model", "static RMS (µm)", "static max (µm)", "path RMS (µm)", "path max (µm)",
           "static preload RMS (N m)", "path preload RMS (N m)"},
          rows);
  if (o.after) {
    d.paragraph(fmt::format("Static error {}× smaller after calibration; path tracking {}×; preload {}×.",
                            ratio_text(o.before->static_rms_um / o.after->static_rms_um),
                            ratio_text(o.before->path_rms_um / o.after->path_rms_um),
                            ratio_text(o.before->static_preload_rms_nm /
                                       std::max(1e-12, o.after->static_preload_rms_nm))));
    const RunAccuracy& ref = o.floor ? *o.floor : *o.after;
    d.paragraph(fmt::format(
        "Static RMS is the tool tip at rest; path RMS is the tool tip while it moves, where the drives' lag behind "
        "the moving target adds an error no calibration removes ({} a path RMS of {} against {} at rest).",
        o.floor ? "the controller given the true parameters and reading errors has" : "the calibrated model has",
        distance(ref.path_rms_um), distance(ref.static_rms_um)));
  }
  if (o.after && o.floor) {
    d.paragraph(fmt::format("The row “actual” is the floor: the controller given the true parameters and the "
                            "twin's transmission and encoder errors (it commands the readings that put the links "
                            "where they should be), so what it leaves is what no model of the geometry and those "
                            "errors removes. The calibrated static RMS is {}× the floor{}. Sampling took {} s of "
                            "robot time.",
                            sig(o.after->static_rms_um / std::max(1e-12, o.floor->static_rms_um), 3),
                            o.floor_ratio_ci95
                                ? fmt::format(" (95 % interval {}-{}, the bootstrap over the test poses)",
                                              sig((*o.floor_ratio_ci95)[0], 3), sig((*o.floor_ratio_ci95)[1], 3))
                                : std::string(),
                            sig(o.robot_time_s, 3)));
  }
}

// Cells of the parameter table for mm and rad parameters: the spread (1σ,
// error, bound) in µm or µrad with its unit in the cell, the values to a
// tenth of the estimate's 1σ.
std::string spread_cell(double v, int i) {
  if (!std::isfinite(v)) return "-";
  return sig(v * (is_offset(i) ? 1e6 : 1e3), 2) + (is_offset(i) ? "\u00a0µrad" : "\u00a0µm");
}
std::string value_cell(double v, double sigma) {
  return std::isfinite(sigma) && sigma > 0.0 ? value_to_sigma(v, sigma) : num(v, 8);
}

// The parameter table: nominal, actual, estimated, 1-sigma, error and the Cramer-Rao bound.
void add_parameters(ReportDocument& d, const RunReport& o, const RunCalibration& r) {
  d.paragraph(fmt::format("{} from {} encoder samples, {} free parameters (fixed: {}). The Cramér-Rao bound (CRB) is "
                          "the smallest 1σ any unbiased estimate could have at the encoders' σ of {} µrad per "
                          "sample.",
                          method_words(r.method, r.cost), o.sample_xy.size(), r.free.count(),
                          format_param_list(~r.free), sig(o.crb_sigma_rad * 1e6, 3)));
  std::vector<std::vector<std::string>> rows;
  for (int i = 0; i < kNumParams; ++i) {
    const size_t k = static_cast<size_t>(i);
    const bool free = r.free.test(k);
    const double err = r.geometry[i] - o.actual[i], s = free ? r.sigma[k] : o.crb[k];
    rows.push_back({std::string(param_name(i)) + " (" + unit(i) + ")", num(o.nominal.geometry[i], 8),
                    value_cell(o.actual[i], s), value_cell(r.geometry[i], s), free ? spread_cell(r.sigma[k], i) : "fixed",
                    free ? spread_cell(err, i) : "-", free ? spread_cell(o.crb[k], i) : "-",
                    free ? sig(std::abs(err) / o.crb[k], 2) : "-"});
  }
  d.table({"parameter", "nominal", "actual", "estimated", "1σ", "error", "CRB σ", "|error| / CRB σ"}, rows);
}

// The solver's diagnostics and its notes (but the model test's diagnosis, already shown).
void add_diagnostics(ReportDocument& d, const RunReport& o, const RunCalibration& r) {
  d.heading(3, "Diagnostics");
  d.table({"cost J", "iterations", "evaluations", "rank", "condition number", "kmrmse (mm)", "seconds", "converged"},
          {{sci(r.final_cost, 4), lm_count_text(r), std::to_string(r.evaluations), std::to_string(r.rank),
            sci(r.condition_number, 3), r.kmrmse_mm ? sci(*r.kmrmse_mm, 3) : "-", sig(r.seconds, 3),
            r.converged ? "yes" : "no"}});
  std::vector<std::string> notes;
  for (const std::string& n : r.notes)
    if (!(o.model_test && n == o.model_test->diagnosis)) notes.push_back(with_unit_symbols(n));
  if (!notes.empty()) d.bullets(notes);
}

// The calibration's section: refused, or its parameters and diagnostics.
void add_calibration(ReportDocument& d, const RunReport& o) {
  d.heading(2, "Calibration");
  if (o.refused) {
    d.paragraph("The calibration was refused, as the scenario expects:");
    d.preformatted(*o.refused);
  }
  if (o.calibration) {
    add_parameters(d, o, *o.calibration);
    add_diagnostics(d, o, *o.calibration);
  }
}

// One row per expectation: its name, pass or FAIL and what was measured.
void add_expectations(ReportDocument& d, const std::vector<RunCheck>& checks) {
  d.heading(2, "Expectations");
  std::vector<std::vector<std::string>> rows;
  for (const RunCheck& c : checks) rows.push_back({c.name, c.passed ? "pass" : "FAIL", with_unit_symbols(c.detail)});
  d.table({"check", "result", "measured"}, rows);
}

// The figures: layout, residuals, convergence, parameter errors and tracking.
void add_figures(ReportDocument& d, const RunReport& o) {
  d.heading(2, "Figures");
  d.figure("layout", "Calibration samples and accuracy test poses over the reachable workspace", layout_figure(o));
  if (o.calibration) {
    d.figure("residuals", "Closure residual of each sample after calibration", residual_figure(o));
    const RunCalibration& r = *o.calibration;
    if (!r.lm_iterations.empty()) {
      d.figure("convergence",
               "Every Levenberg-Marquardt iteration: the cost J (top) and the length of the step tried, in the "
               "solver's parameters (bottom)",
               lm_convergence_figure(r));
    } else if (r.history.size() > 1) {
      d.figure("convergence", "Best cost against error-function evaluations", history_figure(r));
    }
    d.figure("errors_mm", "Base and link errors with their 1σ and the Cramér-Rao bound as a band around zero",
             error_figure(o, false));
    d.figure("errors_offsets", "Offset errors with their 1σ and the Cramér-Rao bound as a band around zero",
             error_figure(o, true));
  }
  if (o.before) d.figure("tracking", "Tracking error along the test path, nominal and calibrated model", tracking_figure(o));
}

}  // namespace

ReportDocument build_run_report(const RunReport& o) {
  ReportDocument d;
  add_verdict(d, o);
  if (o.positioning_um)
    add_positioning(d, *o.positioning_um, o.positioning_bound_um, o.positioning_map);
  else if (o.stated_positioning_um)
    add_stated_positioning(d, *o.stated_positioning_um, o.positioning_map);
  if (o.before) add_accuracy(d, o);
  add_calibration(d, o);
  if (!o.checks.empty()) add_expectations(d, o.checks);
  add_figures(d, o);
  return d;
}

}  // namespace gpm::report
