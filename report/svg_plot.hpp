// Small SVG charts for reports: line, marker and error-bar series on linear
// or log10 axes, with "nice" ticks. Self-contained text, no external assets.
#pragma once

#include <string>
#include <vector>

#include "models/xml_escape.hpp"

namespace gpm::report {

struct Series {
  enum class Style {
    kLine,
    kMarkers,
    kLineMarkers,
    kBand,  // a shaded box y - y_err .. y + y_err at each x, band_width wide (x units)
  };
  enum class Marker { kCircle, kTriangle, kCross };
  std::string label;
  // A line breaks at a point whose x or y is not finite (NaN): one series
  // draws many separate pieces, e.g. arrows.
  std::vector<double> x;
  std::vector<double> y;
  std::vector<double> y_err;  // optional symmetric error bars (same size as y); kBand: the half-height
  Style style = Style::kLine;
  std::string color;          // CSS colour; empty picks from the palette
  Marker marker = Marker::kCircle;
  double marker_size = 3.0;   // marker radius (px)
  double band_width = 0.6;    // kBand only
  double opacity = 1.0;       // fill opacity of markers and bands
  // Optional text beside each point (same size as x, empty strings skipped),
  // e.g. the names of base joints on a layout.
  std::vector<std::string> point_labels;
};

// A vertical line across the plot at x, labelled at its top (an alarm, an event).
struct XMark {
  double x = 0.0;
  std::string label;
  std::string color = "#d62728";
  bool dashed = true;
};

struct PlotOptions {
  std::string title;
  std::string x_label;
  std::string y_label;
  bool log_y = false;         // y plotted as log10 (values <= 0 are skipped)
  bool equal_aspect = false;  // same scale on x and y (for workspace layouts)
  bool integer_x = false;     // x ticks on whole numbers only (iteration counts)
  int width = 640;
  int height = 420;           // the plot; the legend below it adds its own height
  // Optional category labels for x = 0, 1, 2, ... (e.g. parameter names).
  std::vector<std::string> x_categories;
  // Vertical marks drawn over the series (the x range includes them).
  std::vector<XMark> x_marks;
};

// SVG text of a chart of the series.
std::string svg_plot(const std::vector<Series>& series, const PlotOptions& options);

// Plot options with a title and axis labels, the rest at their defaults.
PlotOptions titled_plot(const std::string& title, const std::string& x_label, const std::string& y_label);

// Plot options of a workspace layout: x and y in mm at one scale.
PlotOptions workspace_plot(const std::string& title);

// One SVG of several charts (svg_plot output) stacked top to bottom, as
// panels sharing a caption; as wide as the widest.
std::string svg_stack(const std::vector<std::string>& charts);

// The palette's colour k (12 colours told apart also in print; k wraps).
const char* palette_color(size_t k);

// "Nice" tick positions covering [lo, hi], about `target` of them.
std::vector<double> nice_ticks(double lo, double hi, int target);

// Escapes &, <, >, " for XML text and attributes (models/xml_escape.hpp).
using gpm::xml_escape;

}  // namespace gpm::report
