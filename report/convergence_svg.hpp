// log10(J) against evaluations as an SVG line chart, like paper Figs. 3-5.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace gpm::report {

// One line of the chart: (evaluations, best J) points, a label and a colour.
struct ConvergenceLine {
  std::string label;
  std::string colour;  // SVG colour, e.g. "#1f77b4"
  std::vector<std::pair<long, double>> points;
  bool dashed = false;
};

// A self-contained SVG document: x = evaluations (linear, 0..x_max), y =
// log10(J) (J <= 1e-30 drawn at -30), axes with ticks, a legend and title.
std::string convergence_svg(const std::string& title, long x_max,
                            const std::vector<ConvergenceLine>& lines);

}  // namespace gpm::report
