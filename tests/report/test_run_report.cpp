// Tests of report/run_report.cpp: the figures of a run report show what they
// claim (every LM iteration, the Cramér-Rao bound as a band, the base joints
// and home, a legend inside the figure) and units carry their symbols.
#include "report/run_report.hpp"

#include <regex>

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace gpm::report
