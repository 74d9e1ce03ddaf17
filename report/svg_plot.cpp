#include "report/svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

namespace gpm::report {
namespace {

constexpr const char* kPalette[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e",
                                    "#9467bd", "#8c564b", "#e377c2", "#17becf"};

std::string tick_label(double v, bool log_y) {
  if (log_y) return fmt::format("1e{}", static_cast<int>(std::lround(v)));
  if (v == 0.0) return "0";
  const double a = std::abs(v);
  if (a >= 1e5 || a < 1e-3) return fmt::format("{:.2g}", v);
  return fmt::format("{}", std::round(v * 1e6) / 1e6);
}

}  // namespace

std::vector<double> nice_ticks(double lo, double hi, int target) {
  std::vector<double> ticks;
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return {lo};
  const double raw = (hi - lo) / std::max(1, target);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0}) {
    step = m * mag;
    if (step >= raw) break;
  }
  for (double t = std::ceil(lo / step) * step; t <= hi + 1e-9 * step; t += step) {
    ticks.push_back(std::abs(t) < 1e-12 * step ? 0.0 : t);
  }
  return ticks;
}

std::string svg_plot(const std::vector<Series>& series, const PlotOptions& o) {
  const double left = 70, right = 20, top = o.title.empty() ? 20 : 40, bottom = 55;
  double legend_h = 0;
  for (const Series& s : series) legend_h += s.label.empty() ? 0 : 16;
  const double pw = o.width - left - right, ph = o.height - top - bottom;

  auto ty = [&](double y) { return o.log_y ? std::log10(y) : y; };
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  for (const Series& s : series) {
    for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      const double e = i < s.y_err.size() ? std::abs(s.y_err[i]) : 0.0;
      if (o.log_y && s.y[i] <= 0.0) continue;
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      x0 = std::min(x0, s.x[i]);
      x1 = std::max(x1, s.x[i]);
      const double lo = o.log_y ? ty(std::max(s.y[i] - e, s.y[i] * 1e-3)) : s.y[i] - e;
      y0 = std::min(y0, lo);
      y1 = std::max(y1, ty(s.y[i] + e));
    }
  }
  if (!std::isfinite(x0)) x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  if (!o.x_categories.empty()) x0 = -0.5, x1 = static_cast<double>(o.x_categories.size()) - 0.5;
  if (x1 - x0 <= 0) x0 -= 0.5, x1 += 0.5;
  if (y1 - y0 <= 0) y0 -= std::max(0.5, std::abs(y0) * 0.1), y1 += std::max(0.5, std::abs(y1) * 0.1);
  const double padx = o.x_categories.empty() ? 0.03 * (x1 - x0) : 0.0;
  const double pady = 0.05 * (y1 - y0);
  x0 -= padx, x1 += padx, y0 -= pady, y1 += pady;
  if (o.equal_aspect) {
    const double sx = pw / (x1 - x0), sy = ph / (y1 - y0);
    if (sx > sy) {
      const double c = 0.5 * (x0 + x1), half = 0.5 * pw / sy;
      x0 = c - half, x1 = c + half;
    } else {
      const double c = 0.5 * (y0 + y1), half = 0.5 * ph / sx;
      y0 = c - half, y1 = c + half;
    }
  }
  auto px = [&](double x) { return left + (x - x0) / (x1 - x0) * pw; };
  auto py = [&](double y) { return top + (1.0 - (y - y0) / (y1 - y0)) * ph; };

  std::string svg = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\" viewBox=\"0 0 {} {}\" "
      "font-family=\"sans-serif\" font-size=\"11\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n",
      o.width, o.height + legend_h, o.width, o.height + legend_h);
  if (!o.title.empty()) {
    svg += fmt::format("<text x=\"{}\" y=\"22\" text-anchor=\"middle\" font-size=\"14\">{}</text>\n",
                       o.width / 2, xml_escape(o.title));
  }
  // Grid and ticks.
  const auto yt = o.log_y ? nice_ticks(std::ceil(y0), std::floor(y1), 6) : nice_ticks(y0, y1, 6);
  for (double t : yt) {
    if (o.log_y && std::abs(t - std::round(t)) > 1e-9) continue;
    svg += fmt::format("<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"#ddd\"/>"
                       "<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"end\">{}</text>\n",
                       left, py(t), left + pw, py(t), left - 5, py(t) + 4, tick_label(t, o.log_y));
  }
  if (o.x_categories.empty()) {
    for (double t : nice_ticks(x0, x1, 7)) {
      svg += fmt::format("<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"#ddd\"/>"
                         "<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">{}</text>\n",
                         px(t), top, px(t), top + ph, px(t), top + ph + 15, tick_label(t, false));
    }
  } else {
    for (size_t i = 0; i < o.x_categories.size(); ++i) {
      svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">{}</text>\n",
                         px(static_cast<double>(i)), top + ph + 15, xml_escape(o.x_categories[i]));
    }
  }
  if (!o.log_y && y0 < 0 && y1 > 0) {
    svg += fmt::format("<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"#888\"/>\n",
                       left, py(0), left + pw, py(0));
  }
  svg += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#333\"/>\n",
                     left, top, pw, ph);
  svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">{}</text>\n", left + pw / 2,
                     top + ph + 35, xml_escape(o.x_label));
  svg += fmt::format("<text transform=\"translate(14,{:.1f}) rotate(-90)\" text-anchor=\"middle\">{}</text>\n",
                     top + ph / 2, xml_escape(o.y_label + (o.log_y ? " (log10)" : "")));
  // Series.
  double ly = o.height + 4;
  for (size_t k = 0; k < series.size(); ++k) {
    const Series& s = series[k];
    const std::string color = s.color.empty() ? kPalette[k % 8] : s.color;
    std::string path;
    for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if ((o.log_y && s.y[i] <= 0.0) || !std::isfinite(s.y[i]) || !std::isfinite(s.x[i])) continue;
      const double X = px(s.x[i]), Y = py(ty(s.y[i]));
      if (s.style != Series::Style::kMarkers) path += fmt::format("{}{:.2f},{:.2f}", path.empty() ? "M" : " L", X, Y);
      if (i < s.y_err.size()) {
        const double e = std::abs(s.y_err[i]);
        const double lo = o.log_y ? ty(std::max(s.y[i] - e, s.y[i] * 1e-3)) : s.y[i] - e;
        svg += fmt::format("<line x1=\"{0:.2f}\" y1=\"{1:.2f}\" x2=\"{0:.2f}\" y2=\"{2:.2f}\" stroke=\"{3}\"/>"
                           "<line x1=\"{4:.2f}\" y1=\"{1:.2f}\" x2=\"{5:.2f}\" y2=\"{1:.2f}\" stroke=\"{3}\"/>"
                           "<line x1=\"{4:.2f}\" y1=\"{2:.2f}\" x2=\"{5:.2f}\" y2=\"{2:.2f}\" stroke=\"{3}\"/>\n",
                           X, py(lo), py(ty(s.y[i] + e)), color, X - 4, X + 4);
      }
      if (s.style != Series::Style::kLine) {
        svg += fmt::format("<circle cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"3\" fill=\"{}\"/>\n", X, Y, color);
      }
    }
    if (!path.empty()) {
      svg += fmt::format("<path d=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"1.5\"/>\n", path, color);
    }
    if (!s.label.empty()) {
      svg += fmt::format("<rect x=\"{}\" y=\"{:.1f}\" width=\"12\" height=\"3\" fill=\"{}\"/>"
                         "<text x=\"{}\" y=\"{:.1f}\">{}</text>\n",
                         left, ly + 5, color, left + 18, ly + 10, xml_escape(s.label));
      ly += 16;
    }
  }
  svg += "</svg>\n";
  return svg;
}

}  // namespace gpm::report
