// Small SVG charts for reports: line, marker and error-bar series on linear
// or log10 axes, with "nice" ticks. Self-contained text, no external assets.
#pragma once

#include <string>
#include <vector>

#include "models/xml_escape.hpp"

namespace gpm::report {

struct Series {
  enum class Style { kLine, kMarkers, kLineMarkers };
  std::string label;
  std::vector<double> x;
  std::vector<double> y;
  std::vector<double> y_err;  // optional symmetric error bars (same size as y)
  Style style = Style::kLine;
  std::string color;          // CSS colour; empty picks from the palette
};

struct PlotOptions {
  std::string title;
  std::string x_label;
  std::string y_label;
  bool log_y = false;         // y plotted as log10 (values <= 0 are skipped)
  bool equal_aspect = false;  // same scale on x and y (for workspace layouts)
  int width = 640;
  int height = 420;
  // Optional category labels for x = 0, 1, 2, ... (e.g. parameter names).
  std::vector<std::string> x_categories;
};

// SVG text of a chart of the series.
std::string svg_plot(const std::vector<Series>& series, const PlotOptions& options);

// "Nice" tick positions covering [lo, hi], about `target` of them.
std::vector<double> nice_ticks(double lo, double hi, int target);

// Escapes &, <, >, " for XML text and attributes (models/xml_escape.hpp).
using gpm::xml_escape;

}  // namespace gpm::report
