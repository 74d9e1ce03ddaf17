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

// One marker centred at (x, y).
std::string marker_svg(const Series& s, const std::string& color, double x, double y) {
  const double r = s.marker_size;
  switch (s.marker) {
    case Series::Marker::kTriangle:
      return fmt::format("<polygon points=\"{:.2f},{:.2f} {:.2f},{:.2f} {:.2f},{:.2f}\" fill=\"{}\"/>\n", x,
                         y - 1.3 * r, x - 1.2 * r, y + 0.8 * r, x + 1.2 * r, y + 0.8 * r, color);
    case Series::Marker::kCross:
      return fmt::format("<path d=\"M{0:.2f},{1:.2f} L{2:.2f},{3:.2f} M{0:.2f},{3:.2f} L{2:.2f},{1:.2f}\" "
                         "stroke=\"{4}\" stroke-width=\"2\"/>\n",
                         x - r, y - r, x + r, y + r, color);
    case Series::Marker::kCircle: break;
  }
  if (s.opacity < 1.0)
    return fmt::format("<circle cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"{}\" fill=\"{}\" fill-opacity=\"{}\"/>\n", x, y, r,
                       color, s.opacity);
  return fmt::format("<circle cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"{}\" fill=\"{}\"/>\n", x, y, r, color);
}

// The legend's sample of a series, 24 px wide, centred on (x + 12, y).
std::string legend_swatch(const Series& s, const std::string& color, double x, double y) {
  std::string out;
  if (s.style == Series::Style::kBand) {
    return fmt::format("<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"24\" height=\"10\" fill=\"{}\" fill-opacity=\"{}\"/>\n",
                       x, y - 5, color, s.opacity);
  }
  if (s.style != Series::Style::kMarkers) {
    out += fmt::format("<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"{}\" stroke-width=\"2\"/>\n",
                       x, y, x + 24, y, color);
  }
  if (s.style != Series::Style::kLine) {
    Series big = s;
    big.marker_size = std::max(3.0, s.marker_size);
    big.opacity = 1.0;
    out += marker_svg(big, color, x + 12, y);
  }
  return out;
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
  // The legend: one row of 18 px per labelled series below the plot, and
  // 8 px under the last row for descenders.
  constexpr double kLegendRow = 18;
  double legend_h = 0;
  for (const Series& s : series) legend_h += s.label.empty() ? 0 : kLegendRow;
  if (legend_h > 0) legend_h += 8;
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
  // Ticks as (position on the axis, label). A log axis spanning less than two
  // decades gets round values in between (labelled 5.4e-05, ...).
  std::vector<std::pair<double, std::string>> yt;
  if (o.log_y) {
    for (double t : nice_ticks(std::ceil(y0), std::floor(y1), 6))
      if (std::abs(t - std::round(t)) < 1e-9) yt.emplace_back(t, tick_label(t, true));
    if (yt.size() < 2) {
      yt.clear();
      const auto ticks = nice_ticks(std::pow(10.0, y0), std::pow(10.0, y1), 5);
      // Enough significant digits to tell neighbouring ticks apart.
      const double step = ticks.size() > 1 ? ticks[1] - ticks[0] : 1.0;
      const int digits = std::clamp(
          static_cast<int>(std::ceil(std::log10(std::pow(10.0, y1) / std::max(step, 1e-300)) + 1e-9)) + 1, 2, 15);
      for (double t : ticks)
        if (t > 0.0) yt.emplace_back(std::log10(t), fmt::format("{:.{}g}", t, digits));
    }
  } else {
    for (double t : nice_ticks(y0, y1, 6)) yt.emplace_back(t, tick_label(t, false));
  }
  for (const auto& [t, label] : yt) {
    svg += fmt::format("<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"#ddd\"/>"
                       "<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"end\">{}</text>\n",
                       left, py(t), left + pw, py(t), left - 5, py(t) + 4, label);
  }
  if (o.x_categories.empty()) {
    for (double t : nice_ticks(x0, x1, 7)) {
      if (o.integer_x && std::abs(t - std::round(t)) > 1e-9) continue;
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
  // Series: bands first (behind), then lines, error bars and markers.
  std::vector<size_t> order;
  for (size_t k = 0; k < series.size(); ++k)
    if (series[k].style == Series::Style::kBand) order.push_back(k);
  for (size_t k = 0; k < series.size(); ++k)
    if (series[k].style != Series::Style::kBand) order.push_back(k);
  auto color_of = [&](size_t k) { return series[k].color.empty() ? std::string(kPalette[k % 8]) : series[k].color; };
  for (size_t k : order) {
    const Series& s = series[k];
    const std::string color = color_of(k);
    std::string path;
    for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if ((o.log_y && s.y[i] <= 0.0) || !std::isfinite(s.y[i]) || !std::isfinite(s.x[i])) continue;
      const double X = px(s.x[i]), Y = py(ty(s.y[i]));
      const double e = i < s.y_err.size() ? std::abs(s.y_err[i]) : 0.0;
      const double lo = o.log_y ? ty(std::max(s.y[i] - e, s.y[i] * 1e-3)) : s.y[i] - e;
      if (s.style == Series::Style::kBand) {
        const double half = 0.5 * s.band_width * pw / (x1 - x0);
        svg += fmt::format("<rect x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" height=\"{:.2f}\" fill=\"{}\" "
                           "fill-opacity=\"{}\"/>\n",
                           X - half, py(ty(s.y[i] + e)), 2 * half, std::max(1.0, py(lo) - py(ty(s.y[i] + e))), color,
                           s.opacity);
        continue;
      }
      if (s.style != Series::Style::kMarkers) path += fmt::format("{}{:.2f},{:.2f}", path.empty() ? "M" : " L", X, Y);
      if (i < s.y_err.size()) {
        svg += fmt::format("<line x1=\"{0:.2f}\" y1=\"{1:.2f}\" x2=\"{0:.2f}\" y2=\"{2:.2f}\" stroke=\"{3}\"/>"
                           "<line x1=\"{4:.2f}\" y1=\"{1:.2f}\" x2=\"{5:.2f}\" y2=\"{1:.2f}\" stroke=\"{3}\"/>"
                           "<line x1=\"{4:.2f}\" y1=\"{2:.2f}\" x2=\"{5:.2f}\" y2=\"{2:.2f}\" stroke=\"{3}\"/>\n",
                           X, py(lo), py(ty(s.y[i] + e)), color, X - 4, X + 4);
      }
      if (s.style != Series::Style::kLine) svg += marker_svg(s, color, X, Y);
      if (i < s.point_labels.size() && !s.point_labels[i].empty()) {
        // Beside the point, on the side facing the plot's centre so it stays inside.
        const bool right_half = X > left + pw / 2, top_half = Y < top + ph / 2;
        svg += fmt::format("<text x=\"{:.2f}\" y=\"{:.2f}\" text-anchor=\"{}\" font-weight=\"bold\">{}</text>\n",
                           X + (right_half ? -8.0 : 8.0), Y + (top_half ? 14.0 : -6.0), right_half ? "end" : "start",
                           xml_escape(s.point_labels[i]));
      }
    }
    if (!path.empty()) {
      svg += fmt::format("<path d=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"1.5\"/>\n", path, color);
    }
  }
  // Legend, in the order the series were given.
  double ly = o.height + 4;
  for (size_t k = 0; k < series.size(); ++k) {
    const Series& s = series[k];
    if (s.label.empty()) continue;
    svg += legend_swatch(s, color_of(k), left, ly + 9);
    svg += fmt::format("<text x=\"{}\" y=\"{:.1f}\">{}</text>\n", left + 32, ly + 13, xml_escape(s.label));
    ly += kLegendRow;
  }
  svg += "</svg>\n";
  return svg;
}

}  // namespace gpm::report

namespace gpm::report {
namespace {

// The number in attribute name="..." of the first tag of svg (0 if absent).
double svg_attribute(const std::string& svg, const std::string& name) {
  const size_t end = svg.find('>');
  const size_t at = svg.find(" " + name + "=\"");
  if (at == std::string::npos || at > end) return 0.0;
  return std::stod(svg.substr(at + name.size() + 3));
}

}  // namespace

std::string svg_stack(const std::vector<std::string>& charts) {
  double width = 0, height = 0;
  std::string body;
  for (const std::string& c : charts) {
    const double w = svg_attribute(c, "width"), h = svg_attribute(c, "height");
    // A nested <svg> is placed by its x, y attributes.
    body += fmt::format("<svg x=\"0\" y=\"{}\"", height) + c.substr(c.find("<svg") + 4);
    width = std::max(width, w);
    height += h;
  }
  return fmt::format("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\">\n",
                     width, height) +
         body + "</svg>\n";
}

}  // namespace gpm::report
