// Tests of report/positioning_map_svg.cpp: the arrows' factor against
// hand-worked cases, every point in the band of its error's size, one arrow
// (shaft and two head strokes) per point that has an error, no arrow for
// the robot that positions without error; the stated 1-sigma's map.
#include "report/positioning_map_svg.hpp"

#include <algorithm>
#include <cmath>
#include <regex>

#include <gtest/gtest.h>

namespace gpm::report {
namespace {

TEST(PositioningMapSvg, TheArrowFactorIsTheLargestRoundOneThatFits) {
  EXPECT_DOUBLE_EQ(arrow_scale(4.0, 8.0), 2000.0);    // 4 um x 2000 = 8 mm exactly
  EXPECT_DOUBLE_EQ(arrow_scale(5.0, 8.0), 1000.0);    // 1600 fits; 1000 is the round one below
  EXPECT_DOUBLE_EQ(arrow_scale(1.0, 8.0), 5000.0);    // 8000 fits; 5000
  EXPECT_DOUBLE_EQ(arrow_scale(300.0, 8.0), 20.0);    // 26.7 fits; 20
  EXPECT_DOUBLE_EQ(arrow_scale(0.0, 8.0), 1.0);
  for (double e : {0.37, 3.3, 12.6, 303.0}) {
    const double s = arrow_scale(e, 8.0);
    EXPECT_LE(e * 1e-3 * s, 8.0 + 1e-9);
    EXPECT_GT(e * 1e-3 * s, 8.0 / 2.5 - 1e-9);  // the next round factor up would not fit
  }
}

// The markers drawn in colour c on the map (the legend's sample not counted).
int markers_of(const std::string& svg, const std::string& c) {
  const std::regex marker("<circle[^>]*fill=\"" + c + "\"");
  return static_cast<int>(std::distance(std::sregex_iterator(svg.begin(), svg.end(), marker), std::sregex_iterator())) -
         1;
}

// Pieces (M moves) of the arrows' line.
int arrow_pieces(const std::string& svg) {
  std::smatch m;
  if (!std::regex_search(svg, m, std::regex("<path d=\"(M[^\"]*)\" fill=\"none\" stroke=\"#333333\""))) return 0;
  const std::string d = m[1];
  return static_cast<int>(std::count(d.begin(), d.end(), 'M'));
}

// Errors of 0.5, 1.5, 2.5, 3.5 um (one each) and 0 (two points): bands of
// 1 um, 0-1 holding three points, each other band one; four arrows of three strokes.
TEST(PositioningMapSvg, EveryPointIsInTheBandOfItsErrorWithOneArrow) {
  std::vector<RunPositioningPoint> map;
  const double errors[] = {0.5, 1.5, 2.5, 3.5, 0.0, 0.0};
  for (int i = 0; i < 6; ++i) map.push_back({Eigen::Vector2d(200.0 + 10 * i, 250.0), Eigen::Vector2d(0.0, errors[i])});
  const std::string svg = positioning_map_svg(map);
  EXPECT_NE(svg.find("0–1 µm"), std::string::npos) << svg;
  EXPECT_NE(svg.find("3–4 µm"), std::string::npos);
  EXPECT_EQ(svg.find("4–5 µm"), std::string::npos);
  EXPECT_EQ(markers_of(svg, "#fee8a0"), 3);
  EXPECT_EQ(markers_of(svg, "#fdb863"), 1);
  EXPECT_EQ(markers_of(svg, "#f4743b"), 1);
  EXPECT_EQ(markers_of(svg, "#d7301f"), 1);
  EXPECT_EQ(arrow_pieces(svg), 4 * 3);
  EXPECT_NE(svg.find("error drawn ×2000 (arrow)"), std::string::npos);  // 3.5 um x 2000 = 7 mm
}

TEST(PositioningMapSvg, NoErrorDrawsNoArrow) {
  std::vector<RunPositioningPoint> map{{Eigen::Vector2d(216.5, 250.0), Eigen::Vector2d::Zero()},
                                       {Eigen::Vector2d(226.5, 250.0), Eigen::Vector2d::Zero()}};
  const std::string svg = positioning_map_svg(map);
  EXPECT_EQ(markers_of(svg, "#fee8a0"), 2);
  EXPECT_EQ(arrow_pieces(svg), 0);
}

// The stated 1-sigma's map: bands of sigma_um (1.5, 3.5 and 5.5 um: 0-2, 2-4 and
// 4-6 um), whatever the errors, and no arrow.
TEST(PositioningMapSvg, TheStatedSigmaMapBandsTheSigmaWithoutArrows) {
  std::vector<RunPositioningPoint> map;
  const double sigma[] = {1.5, 3.5, 5.5};
  for (int i = 0; i < 3; ++i)
    map.push_back({Eigen::Vector2d(200.0 + 10 * i, 250.0), Eigen::Vector2d(0.0, 100.0), sigma[i]});
  const std::string svg = stated_sigma_map_svg(map);
  EXPECT_NE(svg.find("4–6 µm"), std::string::npos) << svg;
  EXPECT_EQ(svg.find("6–8 µm"), std::string::npos);
  map.erase(map.begin());  // no point in 0-2 um: the band is left out of the legend
  EXPECT_EQ(stated_sigma_map_svg(map).find("0–2 µm"), std::string::npos);
  EXPECT_EQ(markers_of(svg, "#fee8a0"), 1);
  EXPECT_EQ(markers_of(svg, "#fdb863"), 1);
  EXPECT_EQ(markers_of(svg, "#f4743b"), 1);
  EXPECT_EQ(arrow_pieces(svg), 0);
  EXPECT_EQ(svg.find("(arrow)"), std::string::npos);
}

}  // namespace
}  // namespace gpm::report
