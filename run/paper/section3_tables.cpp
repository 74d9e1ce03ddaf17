#include "run/paper/section3_tables.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include "calib/initial.hpp"
#include "calib/kmrmse.hpp"
#include "calib/lm.hpp"
#include "calib/paper_values.hpp"
#include "calib/synthetic.hpp"
#include "models/kinematics.hpp"

namespace gpm::paper {

namespace {

// Sample poses of section 3.3: the paper does not give them; a disc of this
// radius about home, seeded (the same layout for every error function).
constexpr double kDiscRadiusMm = 100.0;
constexpr std::uint64_t kPoseSeed = 33;

const char* const kStoppingError =
    "Exact readings determine these parameters exactly and Ceres LM reaches them (kmrmse at the rounding "
    "floor); the paper's fmincon stopped at its own tolerance, so its printed value carries that stopping "
    "error (property of the solver, not of the error function).";
const char* const kIterations =
    "Iteration counts belong to the solver: Ceres LM with analytic Jacobians takes its own number of steps, "
    "not fmincon's.";
const char* const kLa3Misprint =
    "Misprint: section 3's actual l_a^3 must be 244.5, not 243.5; every estimator, the paper's included, "
    "returns 244.50 (docs/PAPER_NOTES.md, Tables 3 and 4).";
const char* const kInitialMismatch =
    "The paper's initial estimate is not reproduced to its digits from the reading at (210, 245): the "
    "paper does not say which model it used for this step (open question).";

Robot robot_with(const Geometry& g) {
  Robot r;
  r.geometry = g;
  return r;
}

// "J1", "J2", "J3" as the paper writes them.
std::string cost_label(calib::Cost c) {
  std::string s(calib::cost_name(c));
  for (char& ch : s) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  return s;
}

std::string fixed5(double v) { return fmt::format("{:.5f}", v); }

// Printed text of a parameter value with the paper's decimals for that table.
// decimals < 0: the shortest form ("244.1", "433.05").
std::string printed(double v, int decimals) {
  return decimals < 0 ? fmt::format("{}", v) : fmt::format("{:.{}f}", v, decimals);
}

struct LocalRun {
  calib::Result result;
  double kmrmse = 0.0;
};

LocalRun run_lm(const Robot& actual, const Geometry& start, const FreeMask& free, calib::Cost cost, int n,
                bool allow_rank_deficient = false) {
  const auto poses = calib::disc_poses(actual, n, actual.home, kDiscRadiusMm, kPoseSeed);
  const Samples s = calib::samples_at(actual, poses);
  calib::Problem p;
  p.theta_m = s.theta_m;
  p.start = start;
  p.free = free;
  calib::LmOptions o;
  o.cost = cost;
  o.allow_rank_deficient = allow_rank_deficient;
  o.compute_covariance = false;
  LocalRun r;
  p.true_xy = poses;
  r.result = calib::calibrate_lm(p, o);
  r.kmrmse = r.result.kmrmse_mm.value_or(NAN);
  return r;
}

FreeMask free_of(std::initializer_list<int> params) {
  FreeMask m;
  for (int i : params) m.set(static_cast<size_t>(i));
  return m;
}

const std::array<int, 9> kLinkOrder{kDth1, kDth2, kDth3, kLa1, kLa2, kLa3, kLb1, kLb2, kLb3};

std::string param_label(int i) { return std::string(param_name(i)); }
std::string unit_of(int i) { return is_offset(i) ? "rad" : "mm"; }

}  // namespace

namespace {

// The initial-estimate rows of Tables 3 and 4: this run's (actual l_a^3 =
// 244.5), and dth3 again from a reading of the same mechanism with the
// printed l_a^3 = 243.5, which reproduces the paper's value.
void add_initial_rows(Table& t, const calib::PrintedParams& printed_initial, const Geometry& start,
                      const Robot& model, const Robot& actual) {
  const char* const la3_reading =
      "The paper's initial dth3 comes from a reading of the mechanism with the misprinted l_a^3 = 243.5 (the "
      "next row reproduces it), while its samples used 244.5 (every estimator returns 244.50): the initial "
      "estimate and the data come from two different mechanisms (docs/PAPER_NOTES.md, Tables 3 and 4).";
  for (int i = 0; i < 3; ++i) {
    t.rows.push_back(compare_row(fmt::format("initial estimate dth{}", i + 1), "rad", fixed5(printed_initial[kDth1 + i]),
                                 start[dth(i)], i == 2 ? Reason::kPaperMistake : Reason::kOpen,
                                 i == 2 ? la3_reading : kInitialMismatch));
  }
  Robot misprinted = actual;
  misprinted.geometry[kLa3] = 243.5;
  const Geometry m = reference_start(model, misprinted, kRoughHome);
  t.rows.push_back(compare_row("initial estimate dth3, reading with l_a^3 = 243.5", "rad", fixed5(printed_initial[kDth3]),
                               m[kDth3], Reason::kOpen, kInitialMismatch));
}

}  // namespace

Geometry reference_start(const Robot& model, const Robot& actual, const Eigen::Vector2d& at) {
  const JointAngles q = inverse_kinematics(actual.geometry, at, actual.branch);
  const Eigen::Vector3d m = readings_from_active(actual.geometry, q.theta_a);
  return calib::offsets_from_reference(model, m, model.home);
}

namespace {

// The mechanism of Table 2: nominal links and bases (all links 244 mm) with
// the section-3 offsets (1.0 rad); its readings at (210, 245) give the
// paper's printed initial estimates.
Geometry table2_mechanism() {
  Geometry g = Geometry::gpm2002_nominal();
  for (int i = 0; i < 3; ++i) g[dth(i)] = calib::section3_actual()[dth(i)];
  return g;
}

// The rows "initial estimate dth<i>, section 3's actual values" and the note
// that answers which mechanism the paper used.
void add_table2_mechanism_rows(Table& t, const calib::PrintedTable2& pt, const Geometry& start) {
  const Robot s3 = robot_with(calib::section3_actual());
  const Geometry start_s3 = reference_start(s3, s3, kRoughHome);
  double worst = 0.0;
  for (int i = 0; i < 3; ++i) worst = std::max(worst, std::fabs(start_s3[dth(i)] - pt.initial[i]));
  const std::string why = fmt::format(
      "Read on the mechanism of section 3's actual values (Tables 3 and 4) instead of the nominal one, the "
      "readings at (210, 245) give initial estimates up to {:.2g} rad off the printed ones, beyond their last "
      "digit; the nominal mechanism (all links 244 mm, nominal bases, offsets 1.0) reproduces all three to "
      "every printed digit: the paper simulated Table 2 on the nominal mechanism, and so does this run.",
      worst);
  for (int i = 0; i < 3; ++i) {
    Row r = compare_row(fmt::format("initial estimate dth{}, section 3's actual values", i + 1), "rad",
                        fixed5(pt.initial[i]), start_s3[dth(i)], Reason::kSetup, why);
    r.extra_text = "1.00000";
    t.rows.push_back(r);
  }
  t.notes.push_back(fmt::format(
      "Which mechanism Table 2 used: the readings at (210, 245) of the nominal mechanism with offsets 1.0 give "
      "initial estimates {:.6f}, {:.6f}, {:.6f} (printed {}, {}, {}); those of section 3's actual values give "
      "{:.6f}, {:.6f}, {:.6f}. Table 2's \"actual value\" column lists only the offsets, which both share; its "
      "initial estimates show that its samples came from the nominal links and bases.",
      start[kDth1], start[kDth2], start[kDth3], fixed5(pt.initial[0]), fixed5(pt.initial[1]),
      fixed5(pt.initial[2]), start_s3[kDth1], start_s3[kDth2], start_s3[kDth3]));
}

}  // namespace

Table table2() {
  const calib::PrintedTable2 pt = calib::printed_table2();
  const Robot mechanism = robot_with(table2_mechanism());
  // Links and bases known exactly (section 3.3 A): the model is the simulated mechanism.
  const Geometry start = reference_start(mechanism, mechanism, kRoughHome);
  Table t = make_table("table2", "Table 2. Calibration results of sensor zero positions", fmt::format(
      "Section 3.3 A on generated data: the nominal mechanism (all links 244 mm, nominal bases) with offsets "
      "1.0 rad, the mechanism whose readings give the paper's printed initial estimates (the rows with section "
      "3's actual values show the difference); links and bases known, the three offsets free. Initial offsets "
      "from the encoder readings taken at the rough home guess (210, 245) as if the robot stood at home "
      "(216.5, 250) (section 3.2 step 3). Exact readings at 3 and 9 poses seeded in a disc of radius {} mm "
      "about home; Ceres LM on J1 (eq. 36-37) and J2 (eq. 38-39, row 1 corrected per the errata).",
      kDiscRadiusMm));
  t.extra_column = "actual";
  for (int i = 0; i < 3; ++i) {
    Row r = compare_row(fmt::format("initial estimate dth{}", i + 1), "rad", fixed5(pt.initial[i]),
                        start[dth(i)], Reason::kOpen, kInitialMismatch);
    r.extra_text = "1.00000";
    t.rows.push_back(r);
  }
  add_table2_mechanism_rows(t, pt, start);
  const calib::Cost costs[2] = {calib::Cost::kJ1, calib::Cost::kJ2};
  const int counts[2] = {3, 9};
  for (int c = 0; c < 2; ++c) {
    for (int k = 0; k < 2; ++k) {
      const LocalRun run = run_lm(mechanism, start, free_of({kDth1, kDth2, kDth3}), costs[c], counts[k]);
      const std::string col = fmt::format("{}, {} samples", cost_label(costs[c]), counts[k]);
      for (int i = 0; i < 3; ++i) {
        Row r = compare_row(fmt::format("dth{}, {}", i + 1, col), "rad", fixed5(pt.dth[c][k][i]),
                            run.result.geometry[dth(i)], Reason::kMethod, kStoppingError);
        r.extra_text = "1.00000";
        t.rows.push_back(r);
      }
      t.rows.push_back(compare_row(fmt::format("kmrmse, {}", col), "mm", fmt::format("{:.5e}", pt.kmrmse_mm[c][k]),
                                   run.kmrmse, Reason::kMethod, kStoppingError));
      t.rows.push_back(text_row(fmt::format("iterations, {}", col), "", "(empty)",
                                std::to_string(run.result.iterations), Reason::kSetup,
                                "The paper's table has a row for the iterations but leaves it empty."));
    }
  }
  t.notes.push_back(
      "The paper reads Table 2 as more samples and J2 giving better precision; with exact readings every "
      "column of this run reaches the actual offsets, so the differences it saw are the solver's stopping "
      "error, not information in the samples.");
  return t;
}

Table table3() {
  const calib::PrintedTable3 pt = calib::printed_table3();
  // Table 3 lists no base coordinates: they are known and nominal (its
  // initial estimates are reproduced exactly with them); links nominal in the model.
  Geometry actual_g = calib::section3_actual();
  for (int i = 0; i < 6; ++i) actual_g[i] = Geometry::gpm2002_nominal()[i];
  const Robot actual = robot_with(actual_g);
  const Robot model;
  const Geometry start = reference_start(model, actual, kRoughHome);
  Table t = make_table(
      "table3", "Table 3. Calibration results of sensor zero positions and link lengths",
      "Section 3.3 B on generated data: bases known (nominal: the table lists none), offsets and the six "
      "links free; links start at the "
      "nominal 244 mm, offsets from the readings at (210, 245) with that nominal model. 21 exact samples "
      "in the same disc; Ceres LM on J1, J2 and J3 (eq. 42-43, l_ac and l_as by eq. 41, recovered by eq. 44 "
      "as corrected in the errata).");
  t.extra_column = "actual (this run)";
  for (int i : kLinkOrder) {
    const int dec = is_offset(i) ? 5 : -1;
    Row r = compare_row("actual " + param_label(i), unit_of(i), printed(pt.actual[i], dec), actual_g[i],
                        Reason::kPaperMistake, kLa3Misprint);
    t.rows.push_back(r);
  }
  add_initial_rows(t, pt.initial, start, model, actual);
  const calib::Cost costs[3] = {calib::Cost::kJ1, calib::Cost::kJ2, calib::Cost::kJ3};
  std::array<long, 3> iters{};
  const FreeMask free = free_of({kDth1, kDth2, kDth3, kLa1, kLa2, kLa3, kLb1, kLb2, kLb3});
  for (int c = 0; c < 3; ++c) {
    const LocalRun run = run_lm(actual, start, free, costs[c], 21);
    iters[c] = run.result.iterations;
    const std::string col(cost_label(costs[c]));
    for (int i : kLinkOrder) {
      Row r = compare_row(param_label(i) + ", " + col, unit_of(i), printed(pt.result[c][i], 5),
                          run.result.geometry[i], Reason::kMethod, kStoppingError);
      r.extra_text = format_value(actual_g[i]);
      t.rows.push_back(r);
    }
    t.rows.push_back(compare_row("kmrmse, " + col, "mm", fmt::format("{:.5e}", pt.kmrmse_mm[c]), run.kmrmse,
                                 Reason::kMethod, kStoppingError));
    t.rows.push_back(compare_row("iterations, " + col, "", std::to_string(pt.iterations[c]),
                                 static_cast<double>(run.result.iterations), Reason::kMethod, kIterations));
  }
  t.notes.push_back(fmt::format(
      "The paper finds J3 needs the fewest iterations (46, 47, 33); this run's LM takes {}, {}, {} for J1, J2, "
      "J3{}.",
      iters[0], iters[1], iters[2],
      iters[2] <= std::min(iters[0], iters[1]) ? ", the same ordering" : ", a different ordering"));
  return t;
}

Geometry similarity_point(const Geometry& actual, double rotation) {
  const Eigen::Vector2d a1(actual[kXa1], actual[kYa1]);
  const Eigen::Rotation2Dd turn(rotation);
  const Eigen::Vector2d d2 = turn * (Eigen::Vector2d(actual[kXa2], actual[kYa2]) - a1);
  const double scale = (actual[kYa2] - a1.y()) / d2.y();  // keeps y_a^2
  const Eigen::Vector2d a2 = a1 + scale * d2;
  const Eigen::Vector2d a3 = a1 + scale * (turn * (Eigen::Vector2d(actual[kXa3], actual[kYa3]) - a1));
  Geometry g = actual;
  g[kXa2] = a2.x(), g[kYa2] = a2.y(), g[kXa3] = a3.x(), g[kYa3] = a3.y();
  for (int i = 0; i < 3; ++i) {
    g[dth(i)] += rotation;
    g[kLa1 + i] *= scale;
    g[kLb1 + i] *= scale;
  }
  return g;
}

KmrmsePlacement table4_kmrmse_placement() {
  const calib::PrintedTable4 pt = calib::printed_table4();
  const Geometry actual_g = calib::section3_actual();
  const Robot actual = robot_with(actual_g);
  Geometry initial = actual_g;
  for (int i = 0; i < kNumParams; ++i)
    if (!std::isnan(pt.initial[i])) initial[i] = pt.initial[i];
  KmrmsePlacement k;
  k.rotation = pt.twelve[kDth1] - actual_g[kDth1];
  const Geometry family = similarity_point(actual_g, k.rotation);
  const auto kmrmse_in_disc = [&](const Geometry& g, double radius) {
    const auto poses = calib::disc_poses(actual, 31, actual.home, radius, kPoseSeed);
    return calib::kmrmse(g, calib::samples_at(actual, poses).theta_m, poses);
  };
  k.initial_mm = kmrmse_in_disc(initial, kDiscRadiusMm);
  k.family_mm = kmrmse_in_disc(family, kDiscRadiusMm);
  k.radius_lo_mm = 10.0, k.radius_hi_mm = 150.0;
  k.initial_lo_mm = k.family_lo_mm = INFINITY;
  for (double r = k.radius_lo_mm; r <= k.radius_hi_mm; r += 10.0) {
    const double i = kmrmse_in_disc(initial, r), f = kmrmse_in_disc(family, r);
    k.initial_lo_mm = std::min(k.initial_lo_mm, i), k.initial_hi_mm = std::max(k.initial_hi_mm, i);
    k.family_lo_mm = std::min(k.family_lo_mm, f), k.family_hi_mm = std::max(k.family_hi_mm, f);
  }
  return k;
}

namespace {

// Table 4's printed kmrmse against the initial estimate and the family point at the printed offsets.
void add_kmrmse_placement_rows(Table& t, const KmrmsePlacement& k) {
  const std::string why = fmt::format(
      "The paper prints 3.3521 in the initial-estimation column, beside 34 iterations an initial estimate "
      "cannot have. On exact samples of section 3's mechanism, 31 in a disc about home of radius {:.0f} to "
      "{:.0f} mm, the printed initial estimate has kmrmse {:.3g} to {:.3g} mm ({:.3g} mm on this run's "
      "samples), the point of the similarity family at the printed 12-parameter offsets (rotation {:.4f} rad "
      "about A1) {:.3g} to {:.3g} mm ({:.3g} mm): by value 3.3521 and 34 belong to the 12-parameter column; "
      "the rest of the gap is the paper's samples, which it does not give.",
      k.radius_lo_mm, k.radius_hi_mm, k.initial_lo_mm, k.initial_hi_mm, k.initial_mm, k.rotation,
      k.family_lo_mm, k.family_hi_mm, k.family_mm);
  t.rows.push_back(compare_row("kmrmse of the printed initial estimate", "mm", "3.3521", k.initial_mm,
                               Reason::kPaperMistake, why));
  t.rows.push_back(compare_row("kmrmse of the family point at the printed 12-parameter offsets", "mm", "3.3521",
                               k.family_mm, Reason::kSetup, why));
}

}  // namespace

Table table4() {
  const calib::PrintedTable4 pt = calib::printed_table4();
  const Geometry actual_g = calib::section3_actual();
  const Robot actual = robot_with(actual_g);
  // Section 3.3 C: everything starts nominal (xa1, ya1, ya2 are nominal = true);
  // offsets from the readings at (210, 245).
  const Geometry start = reference_start(Robot{}, actual, kRoughHome);
  const FreeMask twelve = ~free_of({kXa1, kYa1, kYa2});
  Geometry start11 = start;
  start11[kXa2] = actual_g[kXa2];  // "x_a^2 known accurately"
  FreeMask eleven = twelve;
  eleven.reset(kXa2);
  const LocalRun r12 = run_lm(actual, start, twelve, calib::Cost::kJ3, 31, /*allow_rank_deficient=*/true);
  const LocalRun r11 = run_lm(actual, start11, eleven, calib::Cost::kJ3, 31);
  Table t = make_table("table4", "Table 4. Calibration results of 12 parameters", fmt::format(
      "Section 3.3 C on generated data: 31 exact samples in the same disc, J3, nominal start with offsets from "
      "the readings at (210, 245). 12 free parameters (x_a^1, y_a^1, y_a^2 fixed): rank {} of 12, solved with a "
      "minimum-norm LM step; 11 free (x_a^2 fixed at its true value too): rank {} of 11.",
      r12.result.rank, r11.result.rank));
  t.extra_column = "actual (this run)";
  const std::array<int, 12> order{kDth1, kDth2, kDth3, kLa1, kLa2, kLa3, kLb1, kLb2, kLb3, kXa3, kYa3, kXa2};
  const std::string family =
      "Rank 11 of 12: the paper's 12-parameter gauge leaves a one-dimensional family of exact solutions "
      "(scale and rotation about A1; docs/PAPER_NOTES.md), so which point a solver returns depends on its "
      "start and step rule; neither the paper's point nor this run's is the actual mechanism.";
  for (int i : order) {
    const int dec = is_offset(i) ? 5 : -1;
    t.rows.push_back(compare_row("actual " + param_label(i), unit_of(i), printed(pt.actual[i], dec), actual_g[i],
                                 Reason::kPaperMistake, kLa3Misprint));
  }
  add_initial_rows(t, pt.initial, start, Robot{}, actual);
  for (int i : order) {
    Row r = compare_row(param_label(i) + ", 12 free", unit_of(i), printed(pt.twelve[i], 4), r12.result.geometry[i],
                        Reason::kMethod, family);
    r.extra_text = format_value(actual_g[i]);
    t.rows.push_back(r);
  }
  for (int i : order) {
    if (std::isnan(pt.eleven[i])) continue;
    Row r = compare_row(param_label(i) + ", 11 free", unit_of(i), printed(pt.eleven[i], 4), r11.result.geometry[i],
                        Reason::kMethod, kStoppingError);
    r.extra_text = format_value(actual_g[i]);
    t.rows.push_back(r);
  }
  t.rows.push_back(compare_row("kmrmse, 12 free", "mm", "3.3521", r12.kmrmse, Reason::kMethod,
                               "A point of the similarity family moves the computed end-effector by its scale and "
                               "rotation, so kmrmse depends on which point was returned (docs/PAPER_NOTES.md): "
                               "this run's LM point is another one than the paper's."));
  add_kmrmse_placement_rows(t, table4_kmrmse_placement());
  t.rows.push_back(compare_row("kmrmse, 11 free", "mm", "1.0211e-4", r11.kmrmse, Reason::kMethod, kStoppingError));
  t.rows.push_back(compare_row("iterations, 12 free", "", "34", static_cast<double>(r12.result.iterations),
                               Reason::kMethod, kIterations));
  t.rows.push_back(compare_row("iterations, 11 free", "", "70", static_cast<double>(r11.result.iterations),
                               Reason::kMethod, kIterations));
  t.notes.push_back(
      "With x_a^2 fixed too, four base coordinates fix the similarity (rank 11 of 11) and LM recovers every "
      "parameter: the fix is the gauge, not the optimiser. These four are the project's default fixed set.");
  return t;
}

}  // namespace gpm::paper
