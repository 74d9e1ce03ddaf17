#include "report/svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

namespace gpm::report {
namespace {

// The first eight are matplotlib's (earlier figures keep their colours),
// then four more of the same lightness told apart from them.
constexpr const char* kPalette[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b",
                                    "#e377c2", "#17becf", "#7f7f7f", "#bcbd22", "#000080", "#808000"};
constexpr size_t kPaletteSize = sizeof(kPalette) / sizeof(kPalette[0]);

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

namespace {

// The legend's row height (px) per labelled series below the plot.
constexpr double kLegendRow = 18;

// The plot area on the page and the data range it shows (y as log10 on a log axis).
struct Frame {
  double left = 70, right = 20, top = 20, bottom = 55;
  double pw = 0, ph = 0;  // plot area (px)
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  bool log_y = false;
  double ty(double y) const { return log_y ? std::log10(y) : y; }
  double px(double x) const { return left + (x - x0) / (x1 - x0) * pw; }
  double py(double y) const { return top + (1.0 - (y - y0) / (y1 - y0)) * ph; }
};

// The legend's height: one row per labelled series and 8 px under the last row for descenders.
double legend_height(const std::vector<Series>& series) {
  double h = 0;
  for (const Series& s : series) h += s.label.empty() ? 0 : kLegendRow;
  return h > 0 ? h + 8 : 0;
}

// Whether point i of s is drawn (finite, and positive on a log axis).
bool drawn(const Series& s, size_t i, bool log_y) {
  return !(log_y && s.y[i] <= 0.0) && std::isfinite(s.y[i]) && std::isfinite(s.x[i]);
}

// The lower end of point i's error bar in axis units.
double bar_low(const Frame& f, const Series& s, size_t i, double e) {
  return f.log_y ? f.ty(std::max(s.y[i] - e, s.y[i] * 1e-3)) : s.y[i] - e;
}

// Half-length of point i's error bar (0 without one).
double bar_half(const Series& s, size_t i) { return i < s.y_err.size() ? std::abs(s.y_err[i]) : 0.0; }

// The data range of every drawn point with its error bar, padded; a fallback range when empty.
void fit_range(Frame& f, const std::vector<Series>& series, const PlotOptions& o) {
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  for (const Series& s : series) {
    for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if (!drawn(s, i, o.log_y)) continue;
      const double e = bar_half(s, i);
      x0 = std::min(x0, s.x[i]);
      x1 = std::max(x1, s.x[i]);
      y0 = std::min(y0, bar_low(f, s, i, e));
      y1 = std::max(y1, f.ty(s.y[i] + e));
    }
  }
  if (!std::isfinite(x0)) x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  for (const XMark& m : o.x_marks)
    if (std::isfinite(m.x)) x0 = std::min(x0, m.x), x1 = std::max(x1, m.x);
  if (!o.x_categories.empty()) x0 = -0.5, x1 = static_cast<double>(o.x_categories.size()) - 0.5;
  if (x1 - x0 <= 0) x0 -= 0.5, x1 += 0.5;
  if (y1 - y0 <= 0) y0 -= std::max(0.5, std::abs(y0) * 0.1), y1 += std::max(0.5, std::abs(y1) * 0.1);
  const double padx = o.x_categories.empty() ? 0.03 * (x1 - x0) : 0.0;
  const double pady = 0.05 * (y1 - y0);
  f.x0 = x0 - padx, f.x1 = x1 + padx, f.y0 = y0 - pady, f.y1 = y1 + pady;
}

// Widens the range on one axis so that x and y share one scale.
void equalise_aspect(Frame& f) {
  const double sx = f.pw / (f.x1 - f.x0), sy = f.ph / (f.y1 - f.y0);
  if (sx > sy) {
    const double c = 0.5 * (f.x0 + f.x1), half = 0.5 * f.pw / sy;
    f.x0 = c - half, f.x1 = c + half;
  } else {
    const double c = 0.5 * (f.y0 + f.y1), half = 0.5 * f.ph / sx;
    f.y0 = c - half, f.y1 = c + half;
  }
}

// The frame of a chart of the series with options o.
Frame frame_of(const std::vector<Series>& series, const PlotOptions& o) {
  Frame f;
  f.top = o.title.empty() ? 20 : 40;
  f.pw = o.width - f.left - f.right, f.ph = o.height - f.top - f.bottom;
  f.log_y = o.log_y;
  fit_range(f, series, o);
  if (o.equal_aspect) equalise_aspect(f);
  return f;
}

// Ticks on a log axis as (log10 position, label). An axis spanning less than
// two decades gets round values in between (labelled 5.4e-05, ...).
std::vector<std::pair<double, std::string>> log_ticks(const Frame& f) {
  std::vector<std::pair<double, std::string>> yt;
  for (double t : nice_ticks(std::ceil(f.y0), std::floor(f.y1), 6))
    if (std::abs(t - std::round(t)) < 1e-9) yt.emplace_back(t, tick_label(t, true));
  if (yt.size() >= 2) return yt;
  yt.clear();
  const auto ticks = nice_ticks(std::pow(10.0, f.y0), std::pow(10.0, f.y1), 5);
  // Enough significant digits to tell neighbouring ticks apart.
  const double step = ticks.size() > 1 ? ticks[1] - ticks[0] : 1.0;
  const int digits = std::clamp(
      static_cast<int>(std::ceil(std::log10(std::pow(10.0, f.y1) / std::max(step, 1e-300)) + 1e-9)) + 1, 2, 15);
  for (double t : ticks)
    if (t > 0.0) yt.emplace_back(std::log10(t), fmt::format("{:.{}g}", t, digits));
  return yt;
}

// The horizontal grid lines and labels of the y axis.
std::string y_grid_svg(const Frame& f) {
  std::vector<std::pair<double, std::string>> yt;
  if (f.log_y) yt = log_ticks(f);
  else
    for (double t : nice_ticks(f.y0, f.y1, 6)) yt.emplace_back(t, tick_label(t, false));
  std::string svg;
  for (const auto& [t, label] : yt) {
    svg += fmt::format("<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"#ddd\"/>"
                       "<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"end\">{}</text>\n",
                       f.left, f.py(t), f.left + f.pw, f.py(t), f.left - 5, f.py(t) + 4, label);
  }
  return svg;
}

// The vertical grid lines and labels of the x axis (or its category names).
std::string x_grid_svg(const Frame& f, const PlotOptions& o) {
  std::string svg;
  if (!o.x_categories.empty()) {
    for (size_t i = 0; i < o.x_categories.size(); ++i) {
      svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">{}</text>\n",
                         f.px(static_cast<double>(i)), f.top + f.ph + 15, xml_escape(o.x_categories[i]));
    }
    return svg;
  }
  for (double t : nice_ticks(f.x0, f.x1, 7)) {
    if (o.integer_x && std::abs(t - std::round(t)) > 1e-9) continue;
    svg += fmt::format("<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"#ddd\"/>"
                       "<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">{}</text>\n",
                       f.px(t), f.top, f.px(t), f.top + f.ph, f.px(t), f.top + f.ph + 15, tick_label(t, false));
  }
  return svg;
}

// The page, the title, the grid, the zero line, the plot's box and the axis labels.
std::string axes_svg(const Frame& f, const PlotOptions& o, double legend_h) {
  std::string svg = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\" viewBox=\"0 0 {} {}\" "
      "font-family=\"sans-serif\" font-size=\"11\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n",
      o.width, o.height + legend_h, o.width, o.height + legend_h);
  if (!o.title.empty()) {
    svg += fmt::format("<text x=\"{}\" y=\"22\" text-anchor=\"middle\" font-size=\"14\">{}</text>\n",
                       o.width / 2, xml_escape(o.title));
  }
  svg += y_grid_svg(f) + x_grid_svg(f, o);
  if (!f.log_y && f.y0 < 0 && f.y1 > 0) {
    svg += fmt::format("<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"#888\"/>\n",
                       f.left, f.py(0), f.left + f.pw, f.py(0));
  }
  svg += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#333\"/>\n",
                     f.left, f.top, f.pw, f.ph);
  svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">{}</text>\n", f.left + f.pw / 2,
                     f.top + f.ph + 35, xml_escape(o.x_label));
  svg += fmt::format("<text transform=\"translate(14,{:.1f}) rotate(-90)\" text-anchor=\"middle\">{}</text>\n",
                     f.top + f.ph / 2, xml_escape(o.y_label + (o.log_y ? " (log10)" : "")));
  return svg;
}

// Point i of a band series: a shaded box y - e .. y + e, band_width wide.
std::string band_svg(const Frame& f, const Series& s, size_t i, const std::string& color) {
  const double e = bar_half(s, i), X = f.px(s.x[i]);
  const double half = 0.5 * s.band_width * f.pw / (f.x1 - f.x0);
  return fmt::format("<rect x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" height=\"{:.2f}\" fill=\"{}\" "
                     "fill-opacity=\"{}\"/>\n",
                     X - half, f.py(f.ty(s.y[i] + e)), 2 * half,
                     std::max(1.0, f.py(bar_low(f, s, i, e)) - f.py(f.ty(s.y[i] + e))), color, s.opacity);
}

// Point i's error bar, marker and label (its line segment is drawn by series_svg).
std::string point_svg(const Frame& f, const Series& s, size_t i, const std::string& color) {
  std::string svg;
  const double X = f.px(s.x[i]), Y = f.py(f.ty(s.y[i]));
  if (i < s.y_err.size()) {
    const double e = bar_half(s, i);
    svg += fmt::format("<line x1=\"{0:.2f}\" y1=\"{1:.2f}\" x2=\"{0:.2f}\" y2=\"{2:.2f}\" stroke=\"{3}\"/>"
                       "<line x1=\"{4:.2f}\" y1=\"{1:.2f}\" x2=\"{5:.2f}\" y2=\"{1:.2f}\" stroke=\"{3}\"/>"
                       "<line x1=\"{4:.2f}\" y1=\"{2:.2f}\" x2=\"{5:.2f}\" y2=\"{2:.2f}\" stroke=\"{3}\"/>\n",
                       X, f.py(bar_low(f, s, i, e)), f.py(f.ty(s.y[i] + e)), color, X - 4, X + 4);
  }
  if (s.style != Series::Style::kLine) svg += marker_svg(s, color, X, Y);
  if (i < s.point_labels.size() && !s.point_labels[i].empty()) {
    // Beside the point, on the side facing the plot's centre so it stays inside.
    const bool right_half = X > f.left + f.pw / 2, top_half = Y < f.top + f.ph / 2;
    svg += fmt::format("<text x=\"{:.2f}\" y=\"{:.2f}\" text-anchor=\"{}\" font-weight=\"bold\">{}</text>\n",
                       X + (right_half ? -8.0 : 8.0), Y + (top_half ? 14.0 : -6.0), right_half ? "end" : "start",
                       xml_escape(s.point_labels[i]));
  }
  return svg;
}

// One series: its bands, or its error bars, markers and labels and then its line.
std::string series_svg(const Frame& f, const Series& s, const std::string& color) {
  std::string svg, path;
  bool pen_up = true;  // the next point starts a new piece of the line
  for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
    if (!drawn(s, i, f.log_y)) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) pen_up = true;
      continue;
    }
    if (s.style == Series::Style::kBand) {
      svg += band_svg(f, s, i, color);
      continue;
    }
    if (s.style != Series::Style::kMarkers)
      path += fmt::format("{}{:.2f},{:.2f}", pen_up ? (path.empty() ? "M" : " M") : " L", f.px(s.x[i]),
                          f.py(f.ty(s.y[i])));
    pen_up = false;
    svg += point_svg(f, s, i, color);
  }
  if (!path.empty()) svg += fmt::format("<path d=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"1.5\"/>\n", path, color);
  return svg;
}

// Series k's colour: its own, or the palette's.
std::string color_of(const std::vector<Series>& series, size_t k) {
  return series[k].color.empty() ? std::string(kPalette[k % kPaletteSize]) : series[k].color;
}

// The legend below the plot, in the order the series were given.
std::string legend_svg(const Frame& f, const std::vector<Series>& series, const PlotOptions& o) {
  std::string svg;
  double ly = o.height + 4;
  for (size_t k = 0; k < series.size(); ++k) {
    const Series& s = series[k];
    if (s.label.empty()) continue;
    svg += legend_swatch(s, color_of(series, k), f.left, ly + 9);
    svg += fmt::format("<text x=\"{}\" y=\"{:.1f}\">{}</text>\n", f.left + 32, ly + 13, xml_escape(s.label));
    ly += kLegendRow;
  }
  return svg;
}

// The vertical marks, each labelled at the plot's top (a row further down
// for each mark, so labels of close marks do not overlap), on the side
// facing the plot's centre.
std::string x_marks_svg(const Frame& f, const PlotOptions& o) {
  std::string svg;
  double row = 0;
  for (const XMark& m : o.x_marks) {
    if (!std::isfinite(m.x)) continue;
    const double X = f.px(m.x);
    svg += fmt::format("<line x1=\"{0:.2f}\" y1=\"{1:.1f}\" x2=\"{0:.2f}\" y2=\"{2:.1f}\" stroke=\"{3}\" "
                       "stroke-width=\"1.5\"{4}/>\n",
                       X, f.top, f.top + f.ph, m.color, m.dashed ? " stroke-dasharray=\"5,3\"" : "");
    if (m.label.empty()) continue;
    const bool right_half = X > f.left + f.pw / 2;
    svg += fmt::format("<text x=\"{:.2f}\" y=\"{:.1f}\" text-anchor=\"{}\" fill=\"{}\" font-size=\"10\">{}</text>\n",
                       X + (right_half ? -4.0 : 4.0), f.top + 12 + 12 * row, right_half ? "end" : "start", m.color,
                       xml_escape(m.label));
    row = row >= 4 ? 0 : row + 1;
  }
  return svg;
}

}  // namespace

const char* palette_color(size_t k) { return kPalette[k % kPaletteSize]; }

std::string svg_plot(const std::vector<Series>& series, const PlotOptions& o) {
  const Frame f = frame_of(series, o);
  std::string svg = axes_svg(f, o, legend_height(series));
  // Series: bands first (behind), then lines, error bars and markers.
  for (size_t k = 0; k < series.size(); ++k)
    if (series[k].style == Series::Style::kBand) svg += series_svg(f, series[k], color_of(series, k));
  for (size_t k = 0; k < series.size(); ++k)
    if (series[k].style != Series::Style::kBand) svg += series_svg(f, series[k], color_of(series, k));
  svg += x_marks_svg(f, o);
  svg += legend_svg(f, series, o);
  svg += "</svg>\n";
  return svg;
}

PlotOptions titled_plot(const std::string& title, const std::string& x_label, const std::string& y_label) {
  PlotOptions po;
  po.title = title;
  po.x_label = x_label;
  po.y_label = y_label;
  return po;
}

PlotOptions workspace_plot(const std::string& title) {
  PlotOptions po = titled_plot(title, "x (mm)", "y (mm)");
  po.equal_aspect = true;
  return po;
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
