#include "report/convergence_svg.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "report/svg_plot.hpp"

namespace gpm::report {

namespace {

double log_j(double j) { return std::log10(std::max(j, 1e-30)); }

}  // namespace

std::string convergence_svg(const std::string& title, long x_max,
                            const std::vector<ConvergenceLine>& lines) {
  const double W = 760, H = 480, left = 70, right = 170, top = 40, bottom = 55;
  const double pw = W - left - right, ph = H - top - bottom;
  double y_lo = 0, y_hi = 1;
  bool any = false;
  for (const auto& l : lines)
    for (const auto& [e, j] : l.points) {
      if (!std::isfinite(j)) continue;
      const double v = log_j(j);
      y_lo = any ? std::min(y_lo, v) : v;
      y_hi = any ? std::max(y_hi, v) : v;
      any = true;
    }
  y_lo = std::floor(y_lo);
  y_hi = std::ceil(y_hi);
  if (y_hi <= y_lo) y_hi = y_lo + 1;
  const double xm = static_cast<double>(std::max(1L, x_max));
  const auto X = [&](double e) { return left + pw * std::clamp(e / xm, 0.0, 1.0); };
  const auto Y = [&](double v) { return top + ph * (1.0 - (v - y_lo) / (y_hi - y_lo)); };

  std::string s = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\" "
      "font-family=\"sans-serif\" font-size=\"12\">\n"
      "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      "<text x=\"{2}\" y=\"22\" font-size=\"15\" text-anchor=\"middle\">{3}</text>\n",
      W, H, left + pw / 2, xml_escape(title));
  // Axes and ticks.
  s += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"black\"/>\n",
                   left, top, pw, ph);
  for (int i = 0; i <= 5; ++i) {
    const double e = xm * i / 5.0;
    s += fmt::format("<line x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\" stroke=\"#ddd\"/>\n"
                     "<text x=\"{0:.1f}\" y=\"{3}\" text-anchor=\"middle\">{4:.3g}</text>\n",
                     X(e), top, top + ph, top + ph + 18, e);
  }
  const int span = static_cast<int>(y_hi - y_lo);
  const int step = std::max(1, (span + 9) / 10);
  for (int v = static_cast<int>(y_lo); v <= static_cast<int>(y_hi); v += step)
    s += fmt::format("<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"#ddd\"/>\n"
                     "<text x=\"{3}\" y=\"{4:.1f}\" text-anchor=\"end\">{5}</text>\n",
                     left, Y(v), left + pw, left - 6, Y(v) + 4, v);
  s += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">evaluations of the error function</text>\n",
                   left + pw / 2, H - 12);
  s += fmt::format("<text x=\"16\" y=\"{0}\" text-anchor=\"middle\" transform=\"rotate(-90 16 {0})\">log10(J)</text>\n",
                   top + ph / 2);
  // Lines (a step plot: the best value holds until the next improvement).
  int legend = 0;
  for (const auto& l : lines) {
    std::string pts;
    double prev = NAN;
    for (const auto& [e, j] : l.points) {
      if (!std::isfinite(j)) continue;
      const double v = log_j(j);
      if (std::isfinite(prev)) pts += fmt::format("{:.1f},{:.1f} ", X(static_cast<double>(e)), Y(prev));
      pts += fmt::format("{:.1f},{:.1f} ", X(static_cast<double>(e)), Y(v));
      prev = v;
    }
    s += fmt::format("<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"1.6\"{} points=\"{}\"/>\n",
                     l.colour, l.dashed ? " stroke-dasharray=\"5,3\"" : "", pts);
    if (!l.label.empty()) {
      const double ly = top + 10 + 18 * legend++;
      s += fmt::format("<line x1=\"{0}\" y1=\"{1}\" x2=\"{2}\" y2=\"{1}\" stroke=\"{3}\" stroke-width=\"2\"{4}/>\n"
                       "<text x=\"{5}\" y=\"{6}\">{7}</text>\n",
                       left + pw + 10, ly, left + pw + 34, l.colour,
                       l.dashed ? " stroke-dasharray=\"5,3\"" : "", left + pw + 40, ly + 4, xml_escape(l.label));
    }
  }
  s += "</svg>\n";
  return s;
}

}  // namespace gpm::report
