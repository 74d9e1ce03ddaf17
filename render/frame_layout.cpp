#include "render/frame_layout.hpp"

#include <algorithm>
#include <cmath>

namespace gpm::render {

Framing frame_beside_column(const Framing& f, int panel_w, int panel_h, int column_px, int pad_px) {
  const double w_mm = f.hi.x() - f.lo.x(), h_mm = f.hi.y() - f.lo.y();
  const double avail_w = std::max(1, panel_w - column_px - 2 * pad_px);
  const double avail_h = std::max(1, panel_h - 2 * pad_px);
  const double s = std::min(avail_w / std::max(w_mm, 1e-9), avail_h / std::max(h_mm, 1e-9));  // px per mm
  // Left edge of f at column + pad + half the spare width; centred vertically.
  const double left_px = column_px + pad_px + 0.5 * (avail_w - s * w_mm);
  const double bottom_px = pad_px + 0.5 * (avail_h - s * h_mm);
  Framing g;
  g.lo = {f.lo.x() - left_px / s, f.lo.y() - bottom_px / s};
  g.hi = {g.lo.x() + panel_w / s, g.lo.y() + panel_h / s};
  return g;
}

double scale_bar_mm(double px_per_mm, double max_px) {
  if (!(px_per_mm > 0) || !(max_px > 0)) return 0.0;
  const double longest = max_px / px_per_mm;  // mm
  double decade = std::pow(10.0, std::floor(std::log10(longest)));
  for (const double m : {5.0, 2.0, 1.0}) {
    if (m * decade <= longest * (1 + 1e-12)) return m * decade >= 0.1 ? m * decade : 0.0;
  }
  return 0.0;
}

double top_px_per_mm(double distance_m, double z_m, double fovy_deg, int panel_h) {
  const double f = 0.5 * panel_h / std::tan(0.5 * fovy_deg * 3.14159265358979323846 / 180.0);
  return f / (distance_m - z_m) * 1e-3;
}

double error_gain(std::vector<double> errors_mm, double px_per_mm, double target_px) {
  if (errors_mm.empty() || !(px_per_mm > 0) || !(target_px > 0)) return 1.0;
  const auto q = errors_mm.begin() + static_cast<std::ptrdiff_t>(0.95 * static_cast<double>(errors_mm.size() - 1));
  std::nth_element(errors_mm.begin(), q, errors_mm.end());
  if (!(*q > 0)) return 1.0;
  const double most = std::min(1e5, target_px / (*q * px_per_mm));
  if (most < 1.0) return 1.0;
  const double decade = std::pow(10.0, std::floor(std::log10(most) + 1e-12));
  for (const double m : {5.0, 2.0})
    if (m * decade <= most * (1 + 1e-12)) return m * decade;
  return decade;
}

}  // namespace gpm::render
