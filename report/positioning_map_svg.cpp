#include "report/positioning_map_svg.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include "report/svg_plot.hpp"

namespace gpm::report {
namespace {

// Light to dark: the colour bands of |error|, smallest first.
constexpr const char* kBandColors[] = {"#fee8a0", "#fdb863", "#f4743b", "#d7301f", "#990000", "#4d0000"};
constexpr int kBands = static_cast<int>(sizeof(kBandColors) / sizeof(kBandColors[0]));
constexpr double kArrowMm = 8.0;    // the largest arrow's length on the workspace axes
constexpr double kHeadShare = 0.3;  // an arrow head's strokes, as a share of its arrow
constexpr double kHeadAngle = 0.45; // and their angle to the shaft (rad)

// The band width: a round step that splits 0..max_um into at most kBands bands.
double band_step(double max_um) {
  const auto ticks = nice_ticks(0.0, max_um, kBands - 1);
  double step = ticks.size() > 1 ? ticks[1] - ticks[0] : max_um;
  while (std::ceil(max_um / step - 1e-9) > kBands) step *= 2.0;
  return step > 0.0 ? step : 1.0;
}

// What a map colours a point by (um).
using PointValue = double (*)(const RunPositioningPoint&);
double error_size(const RunPositioningPoint& m) { return m.error_um.norm(); }
double stated_sigma(const RunPositioningPoint& m) { return m.sigma_um; }

// The points whose value falls in band k, as one labelled series.
Series band_series(const std::vector<RunPositioningPoint>& map, PointValue value, double step, int k, bool last) {
  Series s;
  s.style = Series::Style::kMarkers;
  s.color = kBandColors[k];
  s.marker_size = 4.0;
  s.label = fmt::format("{:g}–{:g} µm", k * step, (k + 1) * step);
  for (const RunPositioningPoint& m : map) {
    const int band = std::min(static_cast<int>(value(m) / step), kBands - 1);
    if (band == k || (last && band > k)) s.x.push_back(m.p.x()), s.y.push_back(m.p.y());
  }
  return s;
}

// The bands of value over the map that hold a point, smallest first (the
// largest value sets their step).
std::vector<Series> band_series(const std::vector<RunPositioningPoint>& map, PointValue value, double& max_um) {
  max_um = 0.0;
  for (const RunPositioningPoint& m : map) max_um = std::max(max_um, value(m));
  const double step = band_step(max_um);
  const int bands = std::clamp(static_cast<int>(std::ceil(max_um / step - 1e-9)), 1, kBands);
  std::vector<Series> all;
  for (int k = 0; k < bands; ++k) {
    Series s = band_series(map, value, step, k, k == bands - 1);
    if (!s.x.empty()) all.push_back(std::move(s));  // an empty band is left out of the legend too
  }
  return all;
}

// Appends segment a-b to a line series that NaN separates into pieces.
void add_segment(Series& s, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  s.x.insert(s.x.end(), {a.x(), b.x(), std::nan("")});
  s.y.insert(s.y.end(), {a.y(), b.y(), std::nan("")});
}

// Every error as an arrow from its point, error x scale (um to mm).
Series arrow_series(const std::vector<RunPositioningPoint>& map, double scale) {
  Series s;
  s.style = Series::Style::kLine;
  s.color = "#333333";
  s.label = scale >= 1.0 ? fmt::format("error drawn ×{:.0f} (arrow)", scale) : fmt::format("error drawn ×{:g} (arrow)", scale);
  for (const RunPositioningPoint& m : map) {
    const Eigen::Vector2d d = m.error_um * 1e-3 * scale;
    if (d.norm() <= 0.0) continue;
    const Eigen::Vector2d tip = m.p + d;
    add_segment(s, m.p, tip);
    for (double side : {-1.0, 1.0}) {
      const Eigen::Vector2d back = Eigen::Rotation2Dd(side * kHeadAngle) * (-kHeadShare * d);
      add_segment(s, tip, tip + back);
    }
  }
  return s;
}

}  // namespace

double arrow_scale(double max_um, double length_mm) {
  if (!(max_um > 0.0)) return 1.0;
  const double most = length_mm / (max_um * 1e-3);
  const double decade = std::pow(10.0, std::floor(std::log10(most)));
  for (double m : {5.0, 2.0, 1.0})
    if (m * decade <= most * (1.0 + 1e-12)) return m * decade;
  return decade;
}

std::string positioning_map_svg(const std::vector<RunPositioningPoint>& map) {
  double max_um = 0.0;
  std::vector<Series> all = band_series(map, error_size, max_um);
  all.push_back(arrow_series(map, arrow_scale(max_um, kArrowMm)));
  PlotOptions po = workspace_plot("Positioning error of the calibrated model (noise-free)");
  po.height = 440;
  return svg_plot(all, po);
}

std::string stated_sigma_map_svg(const std::vector<RunPositioningPoint>& map) {
  double max_um = 0.0;
  PlotOptions po = workspace_plot("Positioning 1-sigma the calibration states, per axis");
  po.height = 440;
  return svg_plot(band_series(map, stated_sigma, max_um), po);
}

}  // namespace gpm::report
