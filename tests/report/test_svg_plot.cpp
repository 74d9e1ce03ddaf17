// Tests of report/svg_plot.cpp: ticks, escaping, and that points land
// where the axis mapping says.
#include "report/svg_plot.hpp"

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

}  // namespace
}  // namespace gpm::report
