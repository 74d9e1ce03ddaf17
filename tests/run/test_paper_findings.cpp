// Tests of run/paper/section3_tables.cpp and run/paper/section4_tables.cpp's
// findings (similarity_point, table4_kmrmse_placement, table8_consistency,
// reference_start for Table 2) against closed forms and the paper's printed
// values, and of docs/PAPER_NOTES.md: every figure it states about them (and
// the norms of E1's rows, from calib/residuals.hpp) is the one computed here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <fmt/format.h>

#include "calib/kmrmse.hpp"
#include "calib/paper_values.hpp"
#include "calib/residuals.hpp"
#include "calib/synthetic.hpp"
#include "models/data_dir.hpp"
#include "run/paper/closure_costs.hpp"
#include "run/paper/section3_tables.hpp"
#include "run/paper/section4_tables.hpp"
#include "sim/scenario.hpp"

namespace gpm::paper {
namespace {

// docs/PAPER_NOTES.md with every run of white space (line breaks, indents) made one space.
std::string paper_notes() {
  std::ifstream in(std::filesystem::path(GPM_SOURCE_DIR) / "docs" / "PAPER_NOTES.md");
  std::stringstream ss;
  ss << in.rdbuf();
  std::string out;
  for (char c : ss.str()) {
    const bool space = std::isspace(static_cast<unsigned char>(c)) != 0;
    if (space && !out.empty() && out.back() == ' ') continue;
    out += space ? ' ' : c;
  }
  return out;
}

// Expects docs/PAPER_NOTES.md to say `text` word for word.
void expect_notes_say(const std::string& text) {
  static const std::string notes = paper_notes();
  ASSERT_FALSE(notes.empty()) << "docs/PAPER_NOTES.md not read";
  EXPECT_NE(notes.find(text), std::string::npos) << "docs/PAPER_NOTES.md does not say: " << text;
}

Robot robot_of(const Geometry& g) {
  Robot r;
  r.geometry = g;
  return r;
}

TEST(PaperFindings, Table2InitialEstimatesComeFromTheNominalMechanism) {
  const auto printed = calib::printed_table2().initial;
  Geometry nominal = Geometry::gpm2002_nominal();
  for (int i = 0; i < 3; ++i) nominal[dth(i)] = 1.0;
  const Geometry from_nominal = reference_start(robot_of(nominal), robot_of(nominal), kRoughHome);
  const Robot actual = robot_of(calib::section3_actual());
  const Geometry from_actual = reference_start(actual, actual, kRoughHome);
  double worst = 0.0;
  for (int i = 0; i < 3; ++i) {
    // The printed 5 decimals are the nominal mechanism's, rounded.
    EXPECT_EQ(fmt::format("{:.5f}", from_nominal[dth(i)]), fmt::format("{:.5f}", printed[static_cast<size_t>(i)]));
    worst = std::max(worst, std::fabs(from_actual[dth(i)] - printed[static_cast<size_t>(i)]));
  }
  EXPECT_GT(worst, 5e-6);  // beyond the last printed digit
  expect_notes_say(fmt::format("{:.6f}, {:.6f}, {:.6f}", from_nominal[kDth1], from_nominal[kDth2], from_nominal[kDth3]));
  expect_notes_say(fmt::format("{:.6f}, {:.6f}, {:.6f}", from_actual[kDth1], from_actual[kDth2], from_actual[kDth3]));
  expect_notes_say(fmt::format("up to {:.2g} rad off", worst));
}

TEST(PaperFindings, SimilarityPointFitsEveryExactReadingAndMovesTheEndEffectorByItsSimilarity) {
  const Geometry actual = calib::section3_actual();
  const double rotation = 0.0072;
  const Geometry g = similarity_point(actual, rotation);
  EXPECT_EQ(g[kXa1], actual[kXa1]);
  EXPECT_EQ(g[kYa1], actual[kYa1]);
  EXPECT_NEAR(g[kYa2], actual[kYa2], 1e-9);  // the third fixed coordinate
  const auto poses = calib::disc_poses(robot_of(actual), 31, Robot{}.home, 100.0, 5);
  const Samples s = calib::samples_at(robot_of(actual), poses);
  EXPECT_LT(closure_costs(g, s.theta_m).j23, 1e-12);  // an exact solution
  // Closed form: the computed end-effector is A1 + s R (p - A1), so kmrmse = |s R - I| RMS|p - A1|.
  const double scale = g[kLb1] / actual[kLb1];
  const double shift = std::hypot(scale * std::cos(rotation) - 1.0, scale * std::sin(rotation));
  double sum = 0.0;
  for (const auto& p : poses) sum += (p - Eigen::Vector2d(actual[kXa1], actual[kYa1])).squaredNorm();
  EXPECT_NEAR(calib::kmrmse(g, s.theta_m, poses), shift * std::sqrt(sum / 31.0), 1e-9);
}

TEST(PaperFindings, Table4PrintedKmrmseBelongsToTheTwelveParameterColumn) {
  const KmrmsePlacement k = table4_kmrmse_placement();
  const calib::PrintedTable4 pt = calib::printed_table4();
  EXPECT_NEAR(k.rotation, 0.0072, 1e-12);
  // Far from the initial estimate for every disc, about the family point's.
  EXPECT_GT(k.initial_lo_mm, 2.0 * pt.kmrmse_twelve_mm);
  EXPECT_LE(k.family_lo_mm, pt.kmrmse_twelve_mm);
  EXPECT_GE(k.family_hi_mm, pt.kmrmse_twelve_mm);
  // The family point at the printed offsets is the paper's 12-parameter point in the entries that fit it.
  const Geometry family = similarity_point(calib::section3_actual(), k.rotation);
  double fits = 0.0;
  for (int i : {kXa2, kXa3, kYa3, kLb1}) fits = std::max(fits, std::fabs(family[i] - pt.twelve[i]));
  EXPECT_LT(fits, 0.05);
  expect_notes_say(fmt::format("31 in a disc about home of radius {:.0f} to {:.0f} mm", k.radius_lo_mm, k.radius_hi_mm));
  expect_notes_say(fmt::format("kmrmse {:.3g} to {:.3g} mm", k.initial_lo_mm, k.initial_hi_mm));
  expect_notes_say(fmt::format("rotation {:.4f} rad about A1", k.rotation));
  expect_notes_say(fmt::format("to within {:.2f} mm", fits));
  expect_notes_say(fmt::format("has {:.3g} to {:.3g} mm", k.family_lo_mm, k.family_hi_mm));
}

TEST(PaperFindings, Table8PrintedJ3AtTheNominalValuesDoesNotFitItsCalibratedValues) {
  const sim::Scenario sc =
      sim::load_scenario((std::filesystem::path(scenarios_dir()) / "paper_table8_robot.yaml").string());
  ASSERT_TRUE(sc.sampling);
  const Table8Consistency c = table8_consistency(sc.sampling->centre);
  const double printed = calib::printed_table8().j3_nominal;
  EXPECT_GE(c.radius_hi_mm, 80.0);  // the scenario's circle is among them
  EXPECT_GT(c.j3_lo, 10.0 * printed);
  EXPECT_GT(c.j3_anywhere_lo, printed);
  EXPECT_GT(c.circles_anywhere, 100);
  expect_notes_say(fmt::format("{:.2g} to {:.2g} mm^4 for radii {:.0f} to {:.0f} mm", c.j3_lo, c.j3_hi,
                               c.radius_lo_mm, c.radius_hi_mm));
  expect_notes_say(fmt::format("median {:.2g}, {:.0f} times the printed value", c.j3_median, c.j3_median / printed));
  expect_notes_say(fmt::format("lowest over {} reachable circles of radius {:.0f} to {:.0f} mm", c.circles_anywhere,
                               c.radius_anywhere_lo_mm, c.radius_anywhere_hi_mm));
  expect_notes_say(fmt::format("is {:.2g} ({:.1f} times)", c.j3_anywhere_lo, c.j3_anywhere_lo / printed));
}

// The largest relative spread max/min - 1 of the norms of E1's three rows
// (the vectors E1_i of eq. 36) over readings of Table 5's mechanism, at g.
double e1_norm_spread(const Geometry& g) {
  const Samples s = calib::workspace_samples(robot_of(calib::table5_actual()), 20, 7);
  double worst = 0.0;
  for (const Eigen::Vector3d& m : s.theta_m) {
    double r[6];
    EXPECT_TRUE(calib::E1Residual{m}(g.values.data(), r));
    double lo = INFINITY, hi = 0.0;
    for (int i = 0; i < 3; ++i) {
      const double n = std::hypot(r[2 * i], r[2 * i + 1]);
      lo = std::min(lo, n), hi = std::max(hi, n);
    }
    EXPECT_GT(lo, 0.0);
    worst = std::max(worst, hi / lo - 1.0);
  }
  return worst;
}

TEST(PaperNotes, E1RowsHaveEqualNormsOnlyWhenTheThreeLbAreEqual) {
  // Near Table 5's actual values (offsets 1 mrad off, so that E1 is not zero).
  Geometry g = calib::table5_actual();
  for (int i = 0; i < 3; ++i) g[dth(i)] += 1e-3;
  const double spread = e1_norm_spread(g);
  // Closed form: |E1_i| = |P| / (|O - B_i| + l_b^i) with one power P, so the
  // norms stand about as the inverse l_b (small residuals).
  const double lb_ratio = std::max({g[kLb1], g[kLb2], g[kLb3]}) / std::min({g[kLb1], g[kLb2], g[kLb3]}) - 1.0;
  EXPECT_NEAR(spread, lb_ratio, 0.05 * lb_ratio);
  // Equal l_b: equal norms.
  for (int i = 0; i < 3; ++i) g[kLb1 + i] = 244.2;
  EXPECT_LT(e1_norm_spread(g), 1e-9);
  expect_notes_say("E1 have equal norms only when the three l_b are equal");
  expect_notes_say(fmt::format("{:.1f} % apart with Table 5's actual values (l_b {}, {}, {} mm)", 100.0 * spread,
                               calib::table5_actual()[kLb1], calib::table5_actual()[kLb2], calib::table5_actual()[kLb3]));
}

}  // namespace
}  // namespace gpm::paper
