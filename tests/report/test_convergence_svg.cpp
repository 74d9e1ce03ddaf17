// Tests of report/convergence_svg.cpp: a well-formed SVG with one polyline per line.
#include "report/convergence_svg.hpp"

#include <gtest/gtest.h>

namespace gpm::report {
namespace {

size_t count(const std::string& s, const std::string& what) {
  size_t n = 0;
  for (size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + 1)) ++n;
  return n;
}

TEST(ConvergenceSvg, OnePolylinePerLineWithLegendAndAxes) {
  const std::string svg = convergence_svg(
      "J3 <test>", 1000,
      {{"DE", "#1f77b4", {{150, 1e3}, {300, 1e-5}, {1000, 0.0}}, false},
       {"GA", "#d62728", {{100, 1e4}, {1000, 10.0}}, true}});
  EXPECT_EQ(svg.rfind("<svg ", 0), 0u);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  EXPECT_EQ(count(svg, "<polyline"), 2u);
  EXPECT_NE(svg.find("J3 &lt;test&gt;"), std::string::npos);  // escaped title
  EXPECT_NE(svg.find(">DE<"), std::string::npos);
  EXPECT_NE(svg.find("stroke-dasharray"), std::string::npos);
  EXPECT_NE(svg.find(">-30<"), std::string::npos);  // J = 0 drawn at the -30 floor, axis reaches it
  EXPECT_NE(svg.find(">-2<"), std::string::npos);   // ticks every 4 decades up to 1e4
  EXPECT_NE(svg.find("log10(J)"), std::string::npos);
}

}  // namespace
}  // namespace gpm::report
