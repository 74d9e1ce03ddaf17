// Tests of report/svg_plot.cpp: ticks, escaping, that points and bands land
// where the axis mapping says, lines break at NaN, legends inside the
// figure, stacked panels.
#include "report/svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <regex>

#include <gtest/gtest.h>

namespace gpm::report {
namespace {

TEST(SvgPlot, NiceTicksCoverRangeWithRoundSteps) {
  const auto t = nice_ticks(0.0, 1.0, 5);
  ASSERT_EQ(t.size(), 6u);
  EXPECT_DOUBLE_EQ(t[1], 0.2);
  const auto u = nice_ticks(-13.0, 87.0, 5);
  EXPECT_DOUBLE_EQ(u.front(), 0.0);
  EXPECT_DOUBLE_EQ(u[1] - u[0], 20.0);
  EXPECT_LE(u.back(), 87.0);
}

TEST(SvgPlot, EscapesText) {
  EXPECT_EQ(xml_escape("a<b & \"c\">"), "a&lt;b &amp; &quot;c&quot;&gt;");
  PlotOptions o;
  o.title = "J < 1e-18";
  const std::string svg = svg_plot({}, o);
  EXPECT_NE(svg.find("J &lt; 1e-18"), std::string::npos);
}

TEST(SvgPlot, MarkersAreMonotoneInData) {
  Series s;
  s.x = {0, 1, 2};
  s.y = {0, 10, 20};
  s.style = Series::Style::kMarkers;
  const std::string svg = svg_plot({s}, PlotOptions());
  std::regex circle("<circle cx=\"([0-9.]+)\" cy=\"([0-9.]+)\"");
  std::vector<std::pair<double, double>> pts;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), circle); it != std::sregex_iterator(); ++it)
    pts.emplace_back(std::stod((*it)[1]), std::stod((*it)[2]));
  ASSERT_EQ(pts.size(), 3u);
  // x grows to the right, y grows upwards (smaller SVG y), linearly.
  EXPECT_LT(pts[0].first, pts[1].first);
  EXPECT_GT(pts[0].second, pts[1].second);
  EXPECT_NEAR(pts[1].first - pts[0].first, pts[2].first - pts[1].first, 0.02);
  EXPECT_NEAR(pts[0].second - pts[1].second, pts[1].second - pts[2].second, 0.02);
}

// The d attribute of the first line in svg ("" when none).
std::string line_path(const std::string& svg) {
  std::smatch m;
  return std::regex_search(svg, m, std::regex("<path d=\"(M[^\"]*)\" fill=\"none\"")) ? m[1].str() : "";
}

// A line lifts its pen at a NaN point: two pieces, each starting with M,
// and the NaN point not drawn; with it finite, one piece through all five.
TEST(SvgPlot, ALineBreaksAtANaNPoint) {
  Series s;
  s.x = {0, 1, std::nan(""), 2, 3};
  s.y = {0, 1, 5, 0, 1};
  s.style = Series::Style::kLine;
  const std::string two = line_path(svg_plot({s}, PlotOptions()));
  EXPECT_EQ(std::count(two.begin(), two.end(), 'M'), 2) << two;
  EXPECT_EQ(std::count(two.begin(), two.end(), 'L'), 2) << two;
  s.x[2] = 1.5;
  const std::string one = line_path(svg_plot({s}, PlotOptions()));
  EXPECT_EQ(std::count(one.begin(), one.end(), 'M'), 1) << one;
  EXPECT_EQ(std::count(one.begin(), one.end(), 'L'), 4) << one;
}

TEST(SvgPlot, LogAxisSkipsNonPositiveAndSpacesDecadesEqually) {
  Series s;
  s.x = {0, 1, 2, 3};
  s.y = {1e-3, 1e-2, -1.0, 1e-1};
  s.style = Series::Style::kMarkers;
  PlotOptions o;
  o.log_y = true;
  const std::string svg = svg_plot({s}, o);
  std::regex circle("<circle cx=\"([0-9.]+)\" cy=\"([0-9.]+)\"");
  std::vector<double> ys;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), circle); it != std::sregex_iterator(); ++it)
    ys.push_back(std::stod((*it)[2]));
  ASSERT_EQ(ys.size(), 3u);
  EXPECT_NEAR(ys[0] - ys[1], ys[1] - ys[2], 0.02);
}

std::vector<std::pair<double, double>> circles(const std::string& svg) {
  std::regex circle("<circle cx=\"([0-9.]+)\" cy=\"([0-9.]+)\"");
  std::vector<std::pair<double, double>> pts;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), circle); it != std::sregex_iterator(); ++it)
    pts.emplace_back(std::stod((*it)[1]), std::stod((*it)[2]));
  return pts;
}

TEST(SvgPlot, BandSpansValueMinusToPlusItsHalfHeight) {
  // Markers at y = -2, 0, 2 give the axis mapping; a band at 0 +- 1 must
  // span from the pixel of 1 to the pixel of -1 (hand-worked: halfway to the
  // outer markers), and band_width 0.5 of one x unit.
  Series m;
  m.x = {0, 1, 2};
  m.y = {-2, 0, 2};
  m.style = Series::Style::kMarkers;
  Series b;
  b.x = {1};
  b.y = {0};
  b.y_err = {1};
  b.style = Series::Style::kBand;
  b.band_width = 0.5;
  const std::string svg = svg_plot({m, b}, PlotOptions());
  const auto pts = circles(svg);
  ASSERT_EQ(pts.size(), 3u);
  std::smatch r;
  ASSERT_TRUE(std::regex_search(svg, r, std::regex("<rect x=\"([0-9.]+)\" y=\"([0-9.]+)\" width=\"([0-9.]+)\" height=\"([0-9.]+)\" fill=\"[^\"]+\" fill-opacity")));
  const double top = std::stod(r[2]), height = std::stod(r[4]), left = std::stod(r[1]), width = std::stod(r[3]);
  EXPECT_NEAR(top, (pts[2].second + pts[1].second) / 2, 0.02);     // y = +1
  EXPECT_NEAR(height, (pts[0].second - pts[2].second) / 2, 0.02);  // from +1 to -1
  const double unit_px = pts[1].first - pts[0].first;
  EXPECT_NEAR(width, 0.5 * unit_px, 0.02);
  EXPECT_NEAR(left + width / 2, pts[1].first, 0.02);  // centred on x = 1
}

TEST(SvgPlot, LogAxisWithinADecadeGetsReadableTicks) {
  // J from 5.40 to 5.50: no power of ten inside, so round values with enough
  // digits to tell them apart. Hand-worked: the axis pads 5 % of the log
  // range, about 5.395 to 5.506; a fifth of that is 0.022, so the step is
  // 0.025 (the round step above it) and labels need 4 digits.
  Series s;
  s.x = {0, 1, 2};
  s.y = {5.40, 5.45, 5.50};
  PlotOptions o;
  o.log_y = true;
  const std::string svg = svg_plot({s}, o);
  for (const char* t : {">5.4<", ">5.425<", ">5.45<", ">5.475<", ">5.5<"}) EXPECT_NE(svg.find(t), std::string::npos) << t;
  EXPECT_EQ(svg.find(">1e0<"), std::string::npos);
}

TEST(SvgPlot, LegendFitsInsideTheFigure) {
  // Five labelled series: the figure grows by their rows, and the last label's
  // baseline leaves room for descenders (4 px at 11 px type).
  std::vector<Series> all;
  for (int k = 0; k < 5; ++k) {
    Series s;
    s.label = "entry with descenders gjpqy " + std::to_string(k);
    s.x = {0, 1};
    s.y = {0, static_cast<double>(k)};
    s.style = k % 2 ? Series::Style::kMarkers : Series::Style::kLine;
    all.push_back(s);
  }
  PlotOptions o;
  o.height = 300;
  const std::string svg = svg_plot(all, o);
  std::smatch h;
  ASSERT_TRUE(std::regex_search(svg, h, std::regex("<svg [^>]*height=\"([0-9.]+)\"")));
  const double height = std::stod(h[1]);
  EXPECT_GT(height, 300.0 + 5 * 16);
  std::regex last("<text x=\"[0-9.]+\" y=\"([0-9.]+)\">entry with descenders gjpqy 4<");
  std::smatch t;
  ASSERT_TRUE(std::regex_search(svg, t, last));
  EXPECT_LE(std::stod(t[1]) + 4.0, height);
}

TEST(SvgPlot, StackedChartsAddTheirHeights) {
  PlotOptions a, b;
  a.height = 300;
  b.height = 200;
  const std::string top = svg_plot({}, a), bottom = svg_plot({}, b);
  const std::string both = svg_stack({top, bottom});
  EXPECT_EQ(both.rfind("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"640\" height=\"500\"", 0), 0u) << both.substr(0, 120);
  EXPECT_NE(both.find("<svg x=\"0\" y=\"0\""), std::string::npos);
  EXPECT_NE(both.find("<svg x=\"0\" y=\"300\""), std::string::npos);
}

}  // namespace
}  // namespace gpm::report
