// Tests of report/run_report.cpp: the lead sentence (before, after, at the
// tool tip), the verdict with the model test in one voice, valid Markdown
// tables and no Markdown in the HTML, iterations counted as the terminal
// counts them; the figures show what they claim (every LM iteration, the
// Cramér-Rao bound as a band, the base joints and home, a legend inside the
// figure) and units carry their symbols.
#include "report/run_report.hpp"

#include <regex>

#include <gtest/gtest.h>

#include "report_text_checks.hpp"
#include "run_report_fixture.hpp"

namespace gpm::report {
namespace {

std::string figure(const ReportDocument& d, const std::string& file) {
  for (const auto& [name, svg] : d.figure_files())
    if (name == file) return svg;
  ADD_FAILURE() << "no figure " << file;
  return {};
}

size_t count(const std::string& s, const std::regex& re) {
  return static_cast<size_t>(std::distance(std::sregex_iterator(s.begin(), s.end(), re), std::sregex_iterator()));
}

std::vector<double> numbers(const std::string& s, const std::regex& re) {
  std::vector<double> out;
  for (auto it = std::sregex_iterator(s.begin(), s.end(), re); it != std::sregex_iterator(); ++it)
    out.push_back(std::stod((*it)[1]));
  return out;
}

TEST(RunReport, ConvergenceFigureDrawsEveryLmIteration) {
  const RunReport o = testing::run_report_example();
  const std::string svg = figure(build_run_report(o), "convergence.svg");
  int accepted = 0, rejected = 0;
  for (const RunLmIteration& it : o.calibration->lm_iterations) (it.accepted ? accepted : rejected)++;
  ASSERT_EQ(rejected, 2);
  // Accepted iterations are circles (J panel: all; step panel: all but the
  // start), rejected ones crosses in both panels; one legend marker each.
  EXPECT_EQ(count(svg, std::regex("<circle [^>]* r=\"3\"")), static_cast<size_t>(accepted + accepted - 1 + 2));
  EXPECT_EQ(count(svg, std::regex("<path d=\"M[^\"]* M")), static_cast<size_t>(2 * rejected + 2));
  // J spans 10 decades here (1e2 to 1e-8): a log axis with decade ticks at both ends.
  EXPECT_NEAR(o.calibration->final_cost, 1e-8, 1e-20);
  EXPECT_NE(svg.find(">1e-8<"), std::string::npos);
  EXPECT_NE(svg.find(">1e2<"), std::string::npos);
  EXPECT_NE(svg.find("step length"), std::string::npos);
}

TEST(RunReport, WarmStartConvergenceShowsTheChangeOfJ) {
  // J changing by 1e-9 of itself: drawn as J - final J, ticks at that scale.
  RunReport o = testing::run_report_example();
  for (RunLmIteration& it : o.calibration->lm_iterations) it.cost = 5.0 + 1e-9 * it.cost;
  o.calibration->final_cost = o.calibration->lm_iterations.back().cost;
  const std::string svg = figure(build_run_report(o), "convergence.svg");
  EXPECT_NE(svg.find("J − final J"), std::string::npos);
  // J - final J from 1e-9 x (1e2 - 1e-8) at the start down to 0.
  EXPECT_NE(svg.find(">1e-07<"), std::string::npos);
  EXPECT_NE(svg.find(">0<"), std::string::npos);
}

TEST(RunReport, CramerRaoBoundIsABandAroundZero) {
  const RunReport o = testing::run_report_example();
  const std::string svg = figure(build_run_report(o), "errors_mm.svg");
  const std::regex one("<rect x=\"[-0-9.]+\" y=\"([-0-9.]+)\" width=\"[0-9.]+\" height=\"([0-9.]+)\" fill=\"#7f7f7f\" fill-opacity=\"0.45\"");
  const std::regex three("<rect x=\"[-0-9.]+\" y=\"([-0-9.]+)\" width=\"[0-9.]+\" height=\"([0-9.]+)\" fill=\"#7f7f7f\" fill-opacity=\"0.18\"");
  std::vector<std::pair<double, double>> b1, b3;  // (top, height)
  for (auto [re, out] : {std::pair{&one, &b1}, std::pair{&three, &b3}})
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), *re); it != std::sregex_iterator(); ++it)
      out->emplace_back(std::stod((*it)[1]), std::stod((*it)[2]));
  // 8 lengths and base coordinates free (no offsets in this figure), then
  // each band's legend swatch.
  ASSERT_EQ(b1.size(), 9u);
  ASSERT_EQ(b3.size(), 9u);
  for (size_t k = 0; k < 8; ++k) {
    EXPECT_NEAR(b3[k].second / b1[k].second, 3.0, 0.01) << k;  // ±3σ is three times ±1σ
    EXPECT_NEAR(b1[k].first + b1[k].second / 2, b3[k].first + b3[k].second / 2, 0.01) << k;  // same centre
    EXPECT_NEAR(b1[k].first + b1[k].second / 2, b1[0].first + b1[0].second / 2, 0.01) << k;  // zero, shared
  }
  EXPECT_NE(svg.find("Cramér-Rao bound: ±1σ band"), std::string::npos);
}

TEST(RunReport, LayoutMarksBaseJointsAndHomeAndItsLegendFits) {
  const RunReport o = testing::run_report_example();
  const std::string svg = figure(build_run_report(o), "layout.svg");
  for (const char* label : {">A1<", ">A2<", ">A3<", ">home<"}) EXPECT_NE(svg.find(label), std::string::npos) << label;
  const std::vector<double> height = numbers(svg, std::regex("<svg [^>]*height=\"([0-9.]+)\""));
  ASSERT_EQ(height.size(), 1u);
  const std::vector<double> text_y = numbers(svg, std::regex("<text [^>]*y=\"([0-9.]+)\""));
  ASSERT_FALSE(text_y.empty());
  // The lowest baseline (the last legend entry) leaves room for descenders.
  EXPECT_LE(*std::max_element(text_y.begin(), text_y.end()) + 4.0, height[0]);
  EXPECT_NE(svg.find("accuracy test poses"), std::string::npos);
  // 3000 samples are thinned to every 2nd (1500 drawn), not dropped.
  EXPECT_NE(svg.find("1 in 2 of 3000 drawn"), std::string::npos);
}

TEST(RunReport, ResidualFigureKeepsTheOutlierOfALongRun) {
  const RunReport o = testing::run_report_example();
  const std::string svg = figure(build_run_report(o), "residuals.svg");
  // The 900 µrad outlier among +-30 µrad: the axis reaches it.
  EXPECT_NE(svg.find(">800<"), std::string::npos);
  EXPECT_LE(count(svg, std::regex("<circle ")), 2001u);
}

TEST(RunReport, UnitsAreWrittenWithTheirSymbols) {
  const ReportDocument d = build_run_report(testing::run_report_example());
  for (const std::string& text : {d.markdown(), d.html("t")}) {
    EXPECT_NE(text.find("static RMS (µm)"), std::string::npos);
    EXPECT_NE(text.find("28.150 µm calibrated"), std::string::npos);  // from the run library's ASCII detail
    EXPECT_NE(text.find("900 µrad at sample 17"), std::string::npos);
    EXPECT_FALSE(std::regex_search(text, std::regex("[0-9] ?u(m|rad)\\b"))) << "an ASCII unit after a number";
  }
}

// The Markdown's lead: the bold paragraph after the title.
std::string lead(const std::string& md) {
  const size_t a = md.find("\n\n**"), b = md.find("**\n", a + 4);
  return a == std::string::npos || b == std::string::npos ? "" : md.substr(a + 4, b - a - 4);
}

// md with its no-break spaces (between a number and its unit) as spaces.
std::string spaced(const std::string& md) { return std::regex_replace(md, std::regex("\u00a0"), " "); }

TEST(RunReport, LeadsWithBeforeAndAfterAtTheToolTip) {
  const RunReport o = testing::run_report_example();
  const std::string md = spaced(build_run_report(o).markdown());
  // 9681.94 µm -> 9.68 mm, 28.15 µm, 9681.94 / 28.15 = 343.9, 28.15 / 10.71 = 2.63; 8 test poses, 10.07 s.
  EXPECT_EQ(lead(md),
            "With its nominal model the robot's tool tip stood 9.68 mm from where it was sent (RMS over 8 test "
            "poses); calibrated from 3000 of its own encoder readings, taken on the fly in 10 s of robot time (all "
            "the time the calibration keeps the robot from its work), it stands 28.1 µm away: 344× closer, and 2.63× "
            "the error of a controller that knew the true parameters and reading errors (10.7 µm).");
  EXPECT_EQ(md.rfind("# gpm run: example\n\n**With its nominal model", 0), 0u);  // the first paragraph
  // The path against the static error, in one sentence.
  EXPECT_NE(md.find("path RMS is the tool tip while it moves, where the drives' lag behind the moving target adds an "
                    "error no calibration removes (the controller given the true parameters and reading errors has a "
                    "path RMS of 11.8 µm "
                    "against 10.7 µm at rest)"),
            std::string::npos);
  RunReport refused = o;
  refused.refused = "rank 10 of 11";
  refused.calibration.reset();
  EXPECT_EQ(lead(build_run_report(refused).markdown()).rfind("The calibration was refused", 0), 0u);
  EXPECT_NE(build_run_report(o).markdown().find("9.68\u00a0mm"), std::string::npos) << "a line never starts with a unit";
}

TEST(RunReport, AFailedModelTestCoveredByTheStatedSigmaReadsAsSuch) {
  RunReport o = testing::run_report_example();
  for (RunCheck& c : o.checks) c.passed = true;
  o.checks.push_back({"model_test", "chi2 2.844e+05 for 10058 degrees of freedom (fails; expected to fail)", true});
  o.positioning_um = std::array<double, 5>{9.3, 20.1, 10.1, 0.92, 0.0};
  o.model_test->diagnosis = "model test failed (chi2 2.844e+05 for 10058 degrees of freedom, p = 0): residuals are "
                            "5.32x the encoder noise throughout: an unmodelled effect; sample with the redundant joint "
                            "torque-off, or model the effect";
  o.calibration->notes.push_back(o.model_test->diagnosis);
  const std::string md = spaced(build_run_report(o).markdown());
  // sqrt(2.844e5 / 10058) = 5.318; chi2/dof 28.28.
  EXPECT_NE(md.find("Verdict: passed: all 4 expectations of the scenario held. Model test: the readings scatter 5.32× "
                    "the encoders' noise (χ²/dof 28.3, p < 0.001), more than noise alone explains, so the model "
                    "leaves some effect out, as this scenario expects. The stated 1σ accounts for it: the calibrated "
                    "model's positioning error is 0.92× its stated 1σ (1 is honest), so the result stands as stated."),
            std::string::npos)
      << md;
  // The chi-square once, and no advice to do what the procedure already does.
  EXPECT_EQ(count(md, std::regex("χ²|chi2 [0-9]")), 2u) << "the verdict and the expectation's detail";
  EXPECT_EQ(md.find("sample with the redundant joint torque-off"), std::string::npos);
  EXPECT_EQ(md.find("PASSED"), std::string::npos);

  // Not covered: the stated 1-sigma understates the error and the cause is named, once.
  o.positioning_um = std::array<double, 5>{30.0, 60.0, 10.0, 3.0, 0.0};
  const std::string bad = spaced(build_run_report(o).markdown());
  EXPECT_NE(bad.find("The stated 1σ understates the error: the positioning error is 3.0× it. Likely cause: residuals are "
                     "5.32× the encoder noise throughout"),
            std::string::npos)
      << bad;
  EXPECT_EQ(count(bad, std::regex("χ²|chi2 [0-9]")), 2u);

  o.model_test->passed = true;
  EXPECT_NE(build_run_report(o).markdown().find("Model test passed: the readings scatter no more than the encoders' "
                                                 "noise explains (χ²/dof 28.3, p < 0.001)."),
            std::string::npos);
  // With the doubt where a joint may rest expected: (10058 + 502.9) / 10058 = 1.05.
  o.model_test->doubt_chi2 = 502.9;
  EXPECT_NE(build_run_report(o).markdown().find("Model test passed: the readings scatter no more than the encoders' "
                                                 "noise and the friction's doubt explain (χ²/dof 28.3; 1.05 expected "
                                                 "with the doubt where a joint may rest, p < 0.001)."),
            std::string::npos)
      << build_run_report(o).markdown();
}

// The model test's verdict on hand-made outcomes either side of
// kStatedSigmaCovers: chi2 2.844e5 over 10058 dof scatter sqrt(28.28) =
// 5.318x the encoders' 1-sigma; a failed test is covered when the
// positioning error is at most 1.5x the stated 1-sigma, and the terminal's
// line and the report's verdict say the same.
TEST(RunReport, ModelTestVerdictEitherSideOfTheThreshold) {
  EXPECT_EQ(kStatedSigmaCovers, 1.5);
  const ModelTestVerdict covered = model_test_verdict(false, 2.844e5, 10058, 1.49);
  EXPECT_NEAR(covered.scatter, 5.3176, 1e-4);
  EXPECT_TRUE(covered.covered);
  EXPECT_TRUE(model_test_verdict(false, 2.844e5, 10058, kStatedSigmaCovers).covered) << "at the threshold";
  EXPECT_EQ(model_test_verdict_line(covered), "the readings scatter 5.3x the encoders' 1-sigma; the stated 1-sigma "
                                              "accounts for it (positioning error 1.5x the stated 1-sigma)");
  const ModelTestVerdict short_of = model_test_verdict(false, 2.844e5, 10058, 1.51);
  EXPECT_FALSE(short_of.covered);
  EXPECT_EQ(model_test_verdict_line(short_of), "the readings scatter 5.3x the encoders' 1-sigma; the stated 1-sigma "
                                               "understates the error (positioning error 1.5x it; see the report's "
                                               "notes for the likely cause)");
  const ModelTestVerdict unmeasured = model_test_verdict(false, 2.844e5, 10058, std::nullopt);
  EXPECT_FALSE(unmeasured.covered);
  EXPECT_EQ(model_test_verdict_line(unmeasured), "the readings scatter 5.3x the encoders' 1-sigma, more than noise "
                                                 "explains (see the report's notes for the likely cause)");
  const ModelTestVerdict passed = model_test_verdict(true, 2866, 2779, 0.08);
  EXPECT_FALSE(passed.covered) << "a passed test needs no cover";
  EXPECT_EQ(model_test_verdict_line(passed), "the residuals are as small as the encoders explain");

  // The report says the same on each side.
  RunReport o = testing::run_report_example();
  o.model_test->chi2 = 2.844e5;
  o.model_test->dof = 10058;
  o.model_test->passed = false;
  for (const double p : {1.49, 1.51}) {
    o.positioning_um = std::array<double, 5>{9.3, 20.1, 10.1, p, 0.0};
    const std::string md = spaced(build_run_report(o).markdown());
    EXPECT_EQ(md.find("The stated 1σ accounts for it") != std::string::npos, p < kStatedSigmaCovers) << p;
    EXPECT_EQ(md.find("The stated 1σ understates the error") != std::string::npos, p > kStatedSigmaCovers) << p;
  }
}

// The positioning section says how much of the stated 1-sigma the error
// carried unestimated is, and nothing of it when none is carried.
TEST(RunReport, PositioningSaysTheShareOfTheCarriedError) {
  RunReport o = testing::run_report_example();
  o.positioning_um = std::array<double, 5>{9.3, 20.1, 10.1, 0.92, 7.4};
  const std::string md = spaced(build_run_report(o).markdown());
  EXPECT_NE(md.find("Of that 1σ, 7.40 µm (in quadrature) is the error once per joint revolution carried"), std::string::npos)
      << md;
  o.positioning_um = std::array<double, 5>{9.3, 20.1, 10.1, 0.92, 0.0};
  EXPECT_EQ(spaced(build_run_report(o).markdown()).find("Of that 1σ"), std::string::npos);
}

// The floor's paragraph says what the floor knows and, when the run has it,
// the interval of calibrated / floor.
TEST(RunReport, TheFloorsParagraphGivesTheRatiosInterval) {
  RunReport o = testing::run_report_example();
  EXPECT_EQ(spaced(build_run_report(o).markdown()).find("95 % interval"), std::string::npos);
  o.floor_ratio_ci95 = std::array<double, 2>{2.31, 2.97};
  const std::string md = spaced(build_run_report(o).markdown());
  EXPECT_NE(md.find("the twin's transmission and encoder errors"), std::string::npos);
  EXPECT_NE(md.find("is 2.63× the floor (95 % interval 2.31-2.97, the bootstrap over the test poses)"),
            std::string::npos)
      << md;
}

// The positioning section shows the error map when the run measured it, right after its paragraph.
TEST(RunReport, PositioningShowsTheErrorMapWhenMeasured) {
  RunReport o = testing::run_report_example();
  o.positioning_um = std::array<double, 5>{9.3, 20.1, 10.1, 0.92, 0.0};
  EXPECT_EQ(build_run_report(o).markdown().find("positioning.svg"), std::string::npos);
  for (int i = 0; i < 5; ++i)
    o.positioning_map.push_back({o.nominal.home + Eigen::Vector2d(10.0 * i, 0.0), Eigen::Vector2d(4.0 * i, 0.0)});
  const ReportDocument d = build_run_report(o);
  const std::string md = d.markdown();
  const size_t figure = md.find("positioning.svg"), next = md.find("\n## ", md.find("## Positioning error"));
  ASSERT_NE(figure, std::string::npos) << md;
  EXPECT_LT(figure, next);
  const auto files = d.figure_files();
  EXPECT_TRUE(std::any_of(files.begin(), files.end(), [](const auto& f) {
    return f.first == "positioning.svg" && f.second.find("15–20 µm") != std::string::npos;
  }));
}

// Through hardware (no truth): the section states the 1-sigma and its carried
// share, says the error needs the truth, and maps the 1-sigma.
TEST(RunReport, WithoutTheTruthThePositioningSectionStatesTheOneSigma) {
  RunReport o = testing::run_report_example();
  o.stated_positioning_um = std::array<double, 2>{5.46, 3.56};
  for (int i = 0; i < 5; ++i)
    o.positioning_map.push_back({o.nominal.home + Eigen::Vector2d(10.0 * i, 0.0), Eigen::Vector2d::Zero(), 5.0 + i});
  const ReportDocument d = build_run_report(o);
  const std::string md = spaced(d.markdown());
  EXPECT_NE(md.find("## Positioning 1σ of the calibrated model"), std::string::npos) << md;
  EXPECT_NE(md.find("states a positioning 1σ of 5.46 µm per axis"), std::string::npos) << md;
  EXPECT_NE(md.find("Of that 1σ, 3.56 µm (in quadrature)"), std::string::npos) << md;
  EXPECT_NE(md.find("known in simulation only"), std::string::npos);
  EXPECT_NE(md.find("positioning.svg"), std::string::npos);
  // With the truth the error's section comes instead.
  o.positioning_um = std::array<double, 5>{9.3, 20.1, 10.1, 0.92, 0.0};
  EXPECT_EQ(spaced(build_run_report(o).markdown()).find("## Positioning 1σ"), std::string::npos);
}

// The least RMS the readings allow, when the run knows it (the twin's truth), and nothing of it otherwise.
TEST(RunReport, PositioningSaysTheBoundWhenKnown) {
  RunReport o = testing::run_report_example();
  o.positioning_um = std::array<double, 5>{9.3, 20.1, 10.1, 0.92, 7.4};
  EXPECT_EQ(spaced(build_run_report(o).markdown()).find("at best"), std::string::npos);
  o.positioning_bound_um = 6.25;
  const std::string md = spaced(build_run_report(o).markdown());
  EXPECT_NE(md.find("These readings allow an RMS of 6.25 µm at best"), std::string::npos) << md;
  EXPECT_NE(md.find("with that carried error estimated under its prior"), std::string::npos) << md;
  // Nothing carried (the calibration estimated the error): the bound names the error itself.
  o.positioning_um = std::array<double, 5>{9.3, 20.1, 10.1, 0.92, 0.0};
  const std::string estimated = spaced(build_run_report(o).markdown());
  EXPECT_NE(estimated.find("with the error once per joint revolution estimated under its prior"), std::string::npos)
      << estimated;
}

TEST(RunReport, EveryTableIsValidMarkdownAndNoMarkdownLeaksIntoHtml) {
  RunReport o = testing::run_report_example();
  o.positioning_um = std::array<double, 5>{9.3, 20.1, 10.1, 0.92, 0.0};
  const ReportDocument d = build_run_report(o);
  int tables = 0;
  const auto errors = testing::markdown_table_errors(d.markdown(), &tables);
  EXPECT_TRUE(errors.empty()) << errors.front();
  EXPECT_EQ(tables, 4);  // accuracy, parameters, diagnostics, expectations
  EXPECT_NE(d.markdown().find("| parameter | nominal | actual | estimated | 1σ | error | CRB σ | \\|error\\| / CRB σ |"),
            std::string::npos);
  const auto leaks = testing::leaked_markdown(d.html("example"));
  EXPECT_TRUE(leaks.empty()) << leaks.front();
  // The note's C exponents as powers of ten; the method in words.
  EXPECT_NE(d.markdown().find("latch skew s2 -5.53×10⁻⁵ s"), std::string::npos);
  EXPECT_NE(d.markdown().find("Levenberg-Marquardt on the maximum-likelihood residual from 3000 encoder samples"),
            std::string::npos);
  EXPECT_EQ(d.markdown().find("lm on ml"), std::string::npos);
}

TEST(RunReport, ParameterCellsCarryTheirUnitAndTheDigitsTheirSigmaSupports) {
  const RunReport o = testing::run_report_example();
  const std::string md = spaced(build_run_report(o).markdown());
  // la1: actual 244.5 mm, 1-sigma 1e-3 mm -> 4 decimals; estimate -2.5 sigma off; CRB 0.8 sigma.
  EXPECT_NE(md.find("| la1 (mm) | 244 | 244.5000 | 244.4975 | 1.0 µm | -2.5 µm | 0.80 µm | 3.1 |"),
            std::string::npos)
      << md;
  // dth1: 1-sigma 2e-6 rad -> 7 decimals, spreads in µrad.
  EXPECT_NE(md.find("| dth1 (rad) | 0 | 0.0100000 | 0.0099950 | 2.0 µrad | -5.0 µrad | 1.6 µrad | 3.1 |"),
            std::string::npos);
  EXPECT_NE(md.find("| xa1 (mm) | 0 | 0 | 0 | fixed | - | - | - |"), std::string::npos);
}

TEST(RunReport, IterationsAreCountedAsTheTerminalCountsThem) {
  // Three passes (each restarts with an entry that tries no step): the
  // terminal prints the last pass's iterations, the report says so.
  RunReport o = testing::run_report_example();
  std::vector<RunLmIteration> all;
  for (int pass = 0; pass < 3; ++pass)
    for (RunLmIteration it : testing::lm_record(pass == 2 ? 4 : 12, pass == 2 ? std::vector<int>{} : std::vector<int>{3, 6})) {
      it.iteration += all.empty() ? 0 : all.back().iteration + 1;
      all.push_back(it);
    }
  o.calibration->lm_iterations = all;
  o.calibration->iterations = 4;  // Ceres: the last pass's steps
  const ReportDocument d = build_run_report(o);
  const std::string text = "28 iterations in 3 passes (4 in the last)";  // 12 + 12 + 4 steps
  EXPECT_NE(figure(d, "convergence.svg").find("Levenberg-Marquardt: " + text), std::string::npos);
  EXPECT_NE(d.markdown().find("| " + text + " |"), std::string::npos);
  o.calibration->lm_iterations = testing::lm_record(12);
  o.calibration->iterations = 12;
  EXPECT_NE(figure(build_run_report(o), "convergence.svg").find("Levenberg-Marquardt: 12 iterations<"),
            std::string::npos);
}

}  // namespace
}  // namespace gpm::report
