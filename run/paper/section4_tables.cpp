#include "run/paper/section4_tables.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <optional>
#include <vector>

#include <fmt/format.h>

#include "calib/global/comparison.hpp"
#include "calib/global/decision_space.hpp"
#include "calib/global/global.hpp"
#include "calib/kmrmse.hpp"
#include "calib/paper_values.hpp"
#include "calib/synthetic.hpp"
#include "models/data_dir.hpp"
#include "models/errors.hpp"
#include "models/kinematics.hpp"
#include "run/paper/closure_costs.hpp"
#include "sim/simulate.hpp"

namespace gpm::paper {

namespace {

using calib::Cost;
using calib::Method;

constexpr double kPaperBudget = 5e7;
constexpr int kSection4Samples = 50;
constexpr std::uint64_t kDataSeed = 42;

// Table 5 / 7 / 8 order of the 12 parameters.
const std::array<int, 12> kOrder{kYa2, kXa3, kYa3, kLa1, kLa2, kLa3, kLb1, kLb2, kLb3, kDth1, kDth2, kDth3};

std::string unit_of(int i) { return is_offset(i) ? "rad" : "mm"; }
std::string shortest(double v) { return fmt::format("{}", v); }

const char* const kFamily =
    "Rank 11 of 12: with x_a^1, y_a^1, x_a^2 fixed a one-dimensional family of exact solutions remains "
    "(scale and rotation about A1; docs/PAPER_NOTES.md), and DE stops at some point of it that depends on "
    "the seed, the samples and the budget; the paper's point is another one.";

// "J1", "J2", "J3" as the paper writes them.
std::string cost_label(Cost c) {
  std::string s(calib::cost_name(c));
  for (char& ch : s) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  return s;
}

// J1 sums squared lengths, J2 and J3 squared areas.
std::string j_unit(Cost c) { return c == Cost::kJ1 ? "mm^2" : "mm^4"; }

std::string method_label(Method m) {
  switch (m) {
    case Method::kGA: return "GA";
    case Method::kPSO: return "PSO";
    case Method::kDE: return "DE";
    default: return "?";
  }
}

// Why a final J differs from the paper's.
std::pair<Reason, std::string> final_j_reason(Method m, Cost c, double ours, double paper, long budget,
                                              double j2_over_j1) {
  if (ours < 1e-16 && paper < 1e-12) {
    return {Reason::kMethod,
            "Both runs are at the double-precision floor of J (near 1e-19 for 50 samples, docs/PAPER_NOTES.md): "
            "below it the digits are rounding noise, not a better optimum."};
  }
  if (m == Method::kDE && c == Cost::kJ1 && ours < 1e-3 * paper) {
    return {Reason::kOpen,
            "This run's DE reaches the rounding floor of J1 within its budget; nothing in the paper's text "
            "explains why its DE stopped at 2.5e-3 after 5e7 evaluations (open question)."};
  }
  if (c != Cost::kJ1 && m != Method::kDE && ours > paper) {
    return {Reason::kOpen, fmt::format(
        "J2 and J3 are in mm^4: for the same geometry they are about (2 l_b)^2 times J1 (here {:.3g} times at "
        "the nominal values), yet the paper's GA and PSO report J2 and J3 below their J1; either they found "
        "far better points under J2 and J3 or the paper scaled J2 and J3 differently (open question).",
        j2_over_j1)};
  }
  if (ours < paper) {
    return {Reason::kSetup,
            "This run's J is lower than the paper's: its samples, seeds and operator details (GA bit strings, "
            "reinitialisation) are not given, and the J a stochastic search reaches after a fixed budget "
            "varies by orders of magnitude between runs."};
  }
  if (static_cast<double>(budget) < kPaperBudget) {
    return {Reason::kSetup,
            fmt::format("This run stops after {:.3g} evaluations where the paper ran 5e7 (`gpm paper --budget "
                        "5e7` runs the paper's budget).",
                        static_cast<double>(budget))};
  }
  return {Reason::kOpen,
          "With the paper's budget this run's J stays above the paper's; its samples, seeds and operator "
          "details are not given, so the gap is not explained (open question)."};
}

// The log10 J convergence figure of one cost (paper Figs. 3-5).
std::string convergence_svg(const calib::global::Comparison& cmp, Cost cost, int figure) {
  std::vector<report::PaperCurve> curves;
  for (const auto& run : cmp.runs)
    if (run.cost == cost) curves.push_back({method_label(run.method), run.result.history});
  return report::paper_convergence_svg(figure, cost_label(cost), curves);
}

// The comparison of section 4 and what every table of it compares against.
struct Section4Run {
  const Section4Settings& settings;
  const calib::global::Comparison& cmp;
  Geometry nominal = Geometry::gpm2002_nominal();
  Geometry actual = calib::table5_actual();
  double ratio = 0.0;  // J2 (= J3) over J1 at the nominal values for the samples

  // The run of method m on cost c (one seed).
  const calib::global::ComparisonRun& run(Method m, Cost c) const {
    for (const auto& r : cmp.runs)
      if (r.method == m && r.cost == c) return r;
    throw std::logic_error("paper: comparison run missing");
  }
};

constexpr Method kMethods[3] = {Method::kGA, Method::kPSO, Method::kDE};
constexpr Cost kCosts[3] = {Cost::kJ1, Cost::kJ2, Cost::kJ3};

// Table 5: the nominal and actual values and the search box used.
Table table5(const Section4Run& s) {
  Table t = make_table("table5", "Table 5. Value settings for the simulation experiments",
                       "The nominal values, the actual values of the simulated mechanism and the search box used by "
                       "every run of section 4 here (calib/paper_values.cpp table5_actual, calib/global default_box).");
  const calib::Box box = calib::global::default_box(s.nominal, calib::paper_free_mask());
  const double printed_lo[12] = {-5, 428, 495, 239, 239, 239, 239, 239, 239, -0.2, -0.2, -0.2};
  const double printed_hi[12] = {5, 438, 505, 249, 249, 249, 249, 249, 249, 0.2, 0.2, 0.2};
  for (int k = 0; k < 12; ++k) {
    const int i = kOrder[static_cast<size_t>(k)];
    const std::string n(param_name(i));
    t.rows.push_back(compare_row(n + " nominal", unit_of(i), shortest(s.nominal[i]), s.nominal[i], Reason::kOpen,
                                 "The nominal value used differs from the printed one."));
    t.rows.push_back(compare_row(n + " actual", unit_of(i), shortest(s.actual[i]), s.actual[i], Reason::kOpen,
                                 "The actual value used differs from the printed one."));
    t.rows.push_back(compare_row(n + " X_min", unit_of(i), shortest(printed_lo[k]), box.lower[i], Reason::kOpen,
                                 "The search box used differs from the printed one."));
    t.rows.push_back(compare_row(n + " X_max", unit_of(i), shortest(printed_hi[k]), box.upper[i], Reason::kOpen,
                                 "The search box used differs from the printed one."));
  }
  t.notes.push_back("Section 4 fixes x_a^2 where section 3 fixes y_a^2 (docs/PAPER_NOTES.md); the actual x_a^2 "
                    "equals its nominal 433 here, so fixing it at the nominal value fixes it at the truth.");
  return t;
}

// Table 6: the best J of every method on every cost after the budget.
Table table6(const Section4Run& s) {
  Table t = make_table(
      "table6", "Table 6. All the results of the simulation experiments (best J after the budget)",
      fmt::format(
          "GA, PSO and DE (paper section 4.1-4.3 settings: GA N=100, p=1e-4, Pc=0.85, Pm=0.15, tournament 4, "
          "NR=50; PSO N=100, C1=C2=2, w 0.9 to 0.1, NR=50; DE N=150, F=0.5, CR=0.8; eq. 47 with 'and' per the "
          "errata) on J1, J2, J3 with 12 free parameters (x_a^1, y_a^1, x_a^2 fixed), {} exact readings of the "
          "Table 5 mechanism at random reachable workspace points (seed {}), {:.3g} evaluations per run (the "
          "paper: 5e7), seed {}. Identifiability at the actual values: {}",
          kSection4Samples, kDataSeed, static_cast<double>(s.settings.budget), s.settings.seed,
          s.cmp.at_actual.diagnosis));
  for (Cost c : kCosts) {
    for (Method m : kMethods) {
      const double paper = calib::global::paper_table6(m, c);
      const double ours = s.run(m, c).result.final_cost;
      const auto [reason, why] = final_j_reason(m, c, ours, paper, s.settings.budget, s.ratio);
      t.rows.push_back(compare_row(fmt::format("{}, {}", method_label(m), cost_label(c)), j_unit(c),
                                   fmt::format("{:.4e}", paper), ours, reason, why));
    }
  }
  t.notes.push_back(fmt::format("J2 (= J3) over J1 at the nominal values for these samples: {:.4g}.", s.ratio));
  return t;
}

// The row of one method's final J on a figure against the value the text states.
Row final_row(const Section4Run& s, Method m, Cost c, double paper) {
  const double ours = s.run(m, c).result.final_cost;
  if (std::isnan(paper)) {
    return text_row(fmt::format("final {}, {}", cost_label(c), method_label(m)), "", "(not stated)",
                    format_value(ours), Reason::kSetup, "The text states no final value for this curve (Table 6 has it).");
  }
  auto [reason, why] = final_j_reason(m, c, ours, paper, s.settings.budget, s.ratio);
  if (c == Cost::kJ1 && m == Method::kGA) {
    why += " The text's 1.3477e3 also differs from Table 6's 1.3447e3 for the same run (a misprint in one "
           "of them).";
  }
  return compare_row(fmt::format("final {}, {}", cost_label(c), method_label(m)), j_unit(c),
                     fmt::format("{:.4e}", paper), ours, reason, why);
}

// The methods from the worst final J to the best, against the paper's GA, PSO, DE.
Row ranking_row(const Section4Run& s, Cost c) {
  std::vector<std::pair<double, std::string>> order;
  for (Method m : kMethods) order.emplace_back(s.run(m, c).result.final_cost, method_label(m));
  std::sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  const std::string ours_rank = fmt::format("{}, {}, {}", order[0].second, order[1].second, order[2].second);
  const std::string paper_rank = "GA, PSO, DE";
  return text_row("worst to best", "", paper_rank, ours_rank,
                  ours_rank == paper_rank ? Reason::kAgrees : Reason::kSetup,
                  ours_rank == paper_rank
                      ? ""
                      : "With this budget and these samples the ranking differs; GA and PSO are far "
                        "from converged in both, so their order is not a stable property.");
}

// Figure 3, 4 or 5 (cost index ci): the convergence of every method on one cost.
Table convergence_figure(const Section4Run& s, int ci) {
  const Cost c = kCosts[ci];
  Table t = make_table(fmt::format("figure{}", 3 + ci),
                       fmt::format("Figure {}. The performances of the algorithms under function {}", 3 + ci,
                                   cost_label(c)),
                       fmt::format("Best {} so far against error-function evaluations for the runs of Table 6 (the "
                                   "paper plots log10 J). The printed values are the final ones the text of section "
                                   "4.4 states for this figure.",
                                   cost_label(c)));
  t.figure_svg = convergence_svg(s.cmp, c, 3 + ci);
  const auto finals = calib::printed_figure_finals();
  for (int mi = 0; mi < 3; ++mi)
    t.rows.push_back(final_row(s, kMethods[mi], c, finals[static_cast<size_t>(ci)][static_cast<size_t>(mi)]));
  t.rows.push_back(ranking_row(s, c));
  return t;
}

// The note on DE with x_a^1, y_a^1, x_a^2, y_a^2 fixed (the identifiable gauge) on the same samples.
std::string identifiable_note(const Section4Run& s) {
  const FreeMask eleven = default_free_mask();
  const calib::Problem p11 = calib::table5_problem(s.cmp.samples, eleven);
  const calib::Result r11 = calib::global::solve_global(
      p11, Cost::kJ3, Method::kDE, calib::global::default_box(s.nominal, eleven), s.settings.budget, s.settings.seed);
  double err_mm = 0, err_rad = 0;
  for (int i = 0; i < kNumParams; ++i) {
    if (!eleven[static_cast<size_t>(i)]) continue;
    const double e = std::fabs(r11.geometry[i] - s.actual[i]);
    (is_offset(i) ? err_rad : err_mm) = std::max(is_offset(i) ? err_rad : err_mm, e);
  }
  return fmt::format(
      "DE with x_a^1, y_a^1, x_a^2, y_a^2 fixed (rank {} of 11), same samples and budget: J3 = {}, largest "
      "error {} mm and {} rad. Fixing the fourth coordinate, not a better optimiser, is what makes the "
      "answer the actual mechanism.",
      r11.rank, format_value(r11.final_cost), format_value(err_mm), format_value(err_rad));
}

// Table 7: DE's J3 solution against the actual values.
Table table7(const Section4Run& s) {
  const auto& de = s.run(Method::kDE, Cost::kJ3);
  const calib::PrintedTable7 pt = calib::printed_table7();
  Table t = make_table("table7", "Table 7. Calibration results of DE under J3",
                       "The DE run on J3 of Table 6 (12 free parameters) against the actual values (extra column), "
                       "and DE with x_a^2 and y_a^2 both fixed (11 free, identifiable) for comparison.");
  t.extra_column = "actual";
  Geometry printed_g = s.actual;
  for (int i : kOrder) {
    printed_g[i] = pt.de[i];
    Row r = compare_row(std::string(param_name(i)), unit_of(i), fmt::format("{:.4f}", pt.de[i]),
                        de.result.geometry[i], Reason::kMethod, kFamily);
    r.extra_text = shortest(s.actual[i]);
    t.rows.push_back(r);
  }
  t.rows.push_back(compare_row("largest error (lengths and coordinates)", "mm", "0.3530", de.max_error_mm,
                               Reason::kMethod, kFamily));
  t.rows.push_back(compare_row("kmrmse of samples", "mm", "0.0371", de.kmrmse_mm, Reason::kMethod, kFamily));
  // The paper's own solution on this run's samples: its kmrmse is not 0.0371 (errata, Table 7).
  std::vector<Eigen::Vector2d> xy = s.cmp.samples.xy;
  const double printed_kmrmse = calib::kmrmse(printed_g, s.cmp.samples.theta_m, xy);
  t.rows.push_back(compare_row("kmrmse of the paper's printed solution on this run's samples", "mm", "0.0371",
                               printed_kmrmse, Reason::kPaperMistake,
                               fmt::format("The printed solution does not have the stated kmrmse: y_a^2 = 0.3076 "
                                           "is off the similarity family the other entries lie on (the family "
                                           "needs about 0.71), so it does not fit the readings: {} mm on these "
                                           "samples, about 0.19 mm on the errata's (docs/PAPER_NOTES.md, Table 7).",
                                           format_value(printed_kmrmse))));
  t.notes.push_back(identifiable_note(s));
  return t;
}

}  // namespace

Section4Tables section4_tables(const Section4Settings& settings, const EvaluationProgress& progress) {
  if (settings.budget < 1) throw InputError("--budget: must be at least 1 evaluation");
  calib::global::ComparisonSettings st;
  st.budget = settings.budget;
  st.seeds = {settings.seed};
  st.samples = kSection4Samples;
  st.data_seed = kDataSeed;
  st.free = calib::paper_free_mask();
  st.parallel_runs = settings.parallel_runs;
  calib::global::ComparisonProgress cp;
  if (progress) cp = [&](long done, long total, int, int) { progress(done, total); };
  const calib::global::Comparison cmp = calib::global::run_comparison(st, cp);
  Section4Run s{settings, cmp};
  const ClosureCosts at_nominal = closure_costs(s.nominal, cmp.samples.theta_m);
  s.ratio = at_nominal.j23 / at_nominal.j1;
  Section4Tables out;
  out.table5 = table5(s);
  out.table6 = table6(s);
  out.figure3 = convergence_figure(s, 0);
  out.figure4 = convergence_figure(s, 1);
  out.figure5 = convergence_figure(s, 2);
  out.table7 = table7(s);
  return out;
}

namespace {

// Exact readings of robot at n poses on the circle (centre, radius); nullopt when a pose is out of reach.
std::optional<std::vector<Eigen::Vector3d>> circle_readings(const Robot& robot, const Eigen::Vector2d& centre,
                                                            double radius, int n) {
  std::vector<Eigen::Vector2d> poses;
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * M_PI * k / n;
    poses.push_back(centre + radius * Eigen::Vector2d(std::cos(a), std::sin(a)));
    if (!check_reach(robot, poses.back()).ok) return std::nullopt;
  }
  return calib::samples_at(robot, poses).theta_m;
}

// The row that states the inconsistency of Table 8's two printed J3 values.
void add_consistency_row(Table& t, const calib::PrintedTable8& pt, const Table8Consistency& c) {
  const std::string why = fmt::format(
      "The paper's two printed J3 values do not fit eq. 43 together: with its own calibrated values as the "
      "robot, J3 at the nominal values over exact readings at {} poses on a circle about the workspace centre "
      "(as the paper sampled) is {:.2g} to {:.2g} mm^4 for radii {:.0f} to {:.0f} mm (median {:.2g}, {:.0f} "
      "times the printed 2.1517e5), and even the lowest over {} reachable circles of radius {:.0f} to {:.0f} mm "
      "anywhere in the workspace is {:.2g} ({:.1f} times). Either the printed 2.1517e5 or the printed "
      "calibrated values are wrong, or the paper's J3 is not eq. 43.",
      kSection4Samples, c.j3_lo, c.j3_hi, c.radius_lo_mm, c.radius_hi_mm, c.j3_median,
      c.j3_median / pt.j3_nominal, c.circles_anywhere, c.radius_anywhere_lo_mm,
      c.radius_anywhere_hi_mm, c.j3_anywhere_lo, c.j3_anywhere_lo / pt.j3_nominal);
  t.rows.push_back(compare_row("J3 at the nominal values, the paper's calibrated values as the robot (median)",
                               "mm^4", "2.1517e5", c.j3_median, Reason::kPaperMistake, why));
}

}  // namespace

Table8Consistency table8_consistency(const Eigen::Vector2d& centre) {
  const calib::PrintedTable8 pt = calib::printed_table8();
  Robot robot;  // the paper's calibrated values as the robot (x_a^1, y_a^1, x_a^2 as fixed: nominal)
  Geometry nominal = Geometry::gpm2002_nominal();
  for (int i = 0; i < kNumParams; ++i) {
    if (!std::isnan(pt.calibrated[i])) robot.geometry[i] = pt.calibrated[i];
    if (!std::isnan(pt.nominal[i])) nominal[i] = pt.nominal[i];
  }
  Table8Consistency c;
  std::vector<double> about;
  for (double r = 5.0;; r += 5.0) {
    const auto m = circle_readings(robot, centre, r, kSection4Samples);
    if (!m) break;
    about.push_back(closure_costs(nominal, *m).j23);
    c.radius_hi_mm = r;
  }
  if (about.empty()) throw std::logic_error("paper: no reachable circle about the Table 8 centre");
  c.radius_lo_mm = 5.0;
  std::sort(about.begin(), about.end());
  c.j3_lo = about.front(), c.j3_hi = about.back(), c.j3_median = about[about.size() / 2];
  c.radius_anywhere_lo_mm = 10.0, c.radius_anywhere_hi_mm = 150.0;
  c.j3_anywhere_lo = INFINITY;
  for (double x = 100.0; x <= 350.0; x += 10.0) {
    for (double y = 100.0; y <= 400.0; y += 10.0) {
      for (double r = c.radius_anywhere_lo_mm; r <= c.radius_anywhere_hi_mm; r += 10.0) {
        const auto m = circle_readings(robot, {x, y}, r, kSection4Samples);
        if (!m) continue;
        ++c.circles_anywhere;
        c.j3_anywhere_lo = std::min(c.j3_anywhere_lo, closure_costs(nominal, *m).j23);
      }
    }
  }
  return c;
}

Table table8(long evaluations, std::uint64_t seed) {
  const std::string file = (std::filesystem::path(scenarios_dir()) / "paper_table8_robot.yaml").string();
  const sim::Scenario sc = sim::load_scenario(file);
  const sim::SimulationResult simr = sim::run_simulation(sc, [](const sim::LogRow&) {});
  calib::Problem p;
  std::vector<Eigen::Vector2d> xy;
  for (const auto& s : simr.samples) {
    p.theta_m.push_back(s.theta_m);
    xy.push_back(s.xy_mm);
  }
  const Geometry nominal = Geometry::gpm2002_nominal();
  p.start = nominal;  // x_a^1, y_a^1, x_a^2 fixed at their nominal values (= the twin's)
  p.free = calib::paper_free_mask();
  const calib::Result r = calib::global::solve_global(
      p, Cost::kJ3, Method::kDE, calib::global::default_box(nominal, p.free), evaluations, seed);
  const Geometry& actual = simr.actual.geometry;
  const calib::PrintedTable8 pt = calib::printed_table8();
  const double j_nom = closure_costs(nominal, p.theta_m).j23;
  const double j_cal = closure_costs(r.geometry, p.theta_m).j23;
  const double j_act = closure_costs(actual, p.theta_m).j23;

  Table t = make_table("table8", "Table 8. The results of the actual calibration", fmt::format(
      "Section 4.5 on the twin ({}): the real robot is the MuJoCo twin with the Table 5 actual values, "
      "{}-bit encoders with {:.2g} rad noise; {} readings stop-and-go on a circle of radius {} mm about the "
      "workspace centre, as the paper sampled after its straight line failed. DE on J3 with 12 free "
      "parameters (x_a^1, y_a^1, x_a^2 fixed at nominal), Table 5 box, {:.3g} evaluations (the paper: about "
      "1e6), seed {}.",
      std::filesystem::path(file).filename().string(), sc.twin.encoder.bits, sc.twin.encoder.noise_rad,
      p.theta_m.size(), sc.sampling ? sc.sampling->radius : 0.0, static_cast<double>(evaluations), seed));
  t.extra_column = "nominal / twin's actual";
  const std::string robot_differs =
      "A different robot: the paper's GPM2002 is not available, this twin's actual values are Table 5's "
      "(extra column). ";
  for (int i : kOrder) {
    Row row = compare_row(std::string(param_name(i)), unit_of(i),
                          is_offset(i) ? fmt::format("{:.4e}", pt.calibrated[i]) : fmt::format("{:.4f}", pt.calibrated[i]),
                          r.geometry[i], Reason::kSetup, robot_differs + kFamily);
    row.extra_text = shortest(nominal[i]) + " / " + shortest(actual[i]);
    t.rows.push_back(row);
  }
  const std::string j_why = fmt::format(
      "J3 depends on the robot's errors, the sample circle and the encoder noise, none of which are the "
      "paper's; this twin's floor (J3 at its actual values, noise only) is {}.",
      format_value(j_act));
  t.rows.push_back(compare_row("J3 at the nominal values", "mm^4", "2.1517e5", j_nom, Reason::kSetup, j_why));
  t.rows.push_back(compare_row("J3 at the calibrated values", "mm^4", "3.1841e2", j_cal, Reason::kSetup, j_why));
  t.rows.push_back(compare_row("J3 reduction (nominal / calibrated)", "", fmt::format("{:.4g}", pt.j3_nominal / pt.j3_calibrated),
                               j_nom / j_cal, Reason::kSetup, j_why));
  add_consistency_row(t, pt, table8_consistency(sc.sampling ? sc.sampling->centre : Robot{}.home));
  double err_mm = 0;
  for (int i : kOrder)
    if (!is_offset(i)) err_mm = std::max(err_mm, std::fabs(r.geometry[i] - actual[i]));
  t.notes.push_back(fmt::format(
      "J3 at the twin's actual values: {}; DE's J3 {} it. Largest error of the calibrated lengths and "
      "coordinates against the twin's actual values: {} mm, because the 12-parameter gauge is rank 11: a low "
      "J3 does not mean the actual parameters (docs/PAPER_NOTES.md).",
      format_value(j_act), j_cal <= j_act ? "is at or below" : "is above", format_value(err_mm)));
  return t;
}

}  // namespace gpm::paper
