// The positioning error map of a calibrated model as an SVG chart: each
// point of the workspace grid coloured by the size of its error, and the
// error drawn from it as an arrow, scaled up by a round factor so the
// largest arrow is a few millimetres long on the workspace's own axes.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace gpm::report {

// One point of the map (calib/positioning_error.hpp, in the report's units).
struct RunPositioningPoint {
  Eigen::Vector2d p = Eigen::Vector2d::Zero();         // commanded position (mm)
  Eigen::Vector2d error_um = Eigen::Vector2d::Zero();  // where the robot stands - p (um)
  double sigma_um = 0.0;                               // the stated 1-sigma per axis there (um)
};

// The factor the arrows are drawn at: the largest of 1, 2 or 5 times a power
// of ten whose largest arrow (max_um) is at most length_mm long (1 when
// max_um is 0).
double arrow_scale(double max_um, double length_mm);

// SVG text of the map: points in colour bands of |error| (round steps, from
// light to dark; a band without a point is not drawn), arrows error_um x arrow_scale(max, 8 mm), the disc at one
// scale on x and y. An empty map gives an empty chart.
std::string positioning_map_svg(const std::vector<RunPositioningPoint>& map);

// SVG text of the map of the stated 1-sigma: points in colour bands of
// sigma_um as positioning_map_svg's, no arrows (no error known).
std::string stated_sigma_map_svg(const std::vector<RunPositioningPoint>& map);

}  // namespace gpm::report
