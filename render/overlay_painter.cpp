#include "render/overlay_painter.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "models/mjcf.hpp"
#include "render/mechanism_pose.hpp"
#include "report/table_cell.hpp"

namespace gpm::render {
namespace {

// Beyond this many points a polyline is thinned further (every k-th point):
// each segment is one geom, and geoms cost render time.
constexpr size_t kMaxPolylinePoints = 1500;

constexpr double kBaseRadius_m = 0.022;
constexpr double kBaseHalfHeight_m = 0.004;
constexpr double kMarkerHalfHeight_m = 0.001;
constexpr double kLeastMm = 1e-6;  // 1 nm: distances below it are written "< 0.001 um"
constexpr double kBarbRad = 0.5235987755982988;  // 30 degrees
constexpr std::array<float, 4> kFloorRgba = {0.13f, 0.14f, 0.16f, 1.0f};

template <class T, class F>
std::vector<T> thin(const std::vector<T>& in, double spacing_mm, F pos) {
  std::vector<T> out;
  for (const T& v : in) {
    if (out.empty() || (pos(v) - pos(out.back())).norm() >= spacing_mm) out.push_back(v);
  }
  if (!in.empty() && (out.size() < 2 || pos(out.back()) != pos(in.back()))) out.push_back(in.back());
  if (out.size() > kMaxPolylinePoints) {
    const size_t k = (out.size() + kMaxPolylinePoints - 1) / kMaxPolylinePoints;
    std::vector<T> sparse;
    for (size_t i = 0; i < out.size(); i += k) sparse.push_back(out[i]);
    if (sparse.back() != out.back()) sparse.push_back(out.back());
    out.swap(sparse);
  }
  return out;
}

mjvGeom* next_geom(mjvScene* scn) {
  if (scn->ngeom >= scn->maxgeom) return nullptr;
  return &scn->geoms[scn->ngeom++];
}

void init_decor(mjvGeom* g, int type, const mjtNum size[3], const mjtNum pos[3], const float rgba[4],
                float emission) {
  mjv_initGeom(g, type, size, pos, nullptr, rgba);
  // mjv_initGeom makes some shapes round in every axis: keep the given size.
  if (size)
    for (int i = 0; i < 3; ++i) g->size[i] = static_cast<float>(size[i]);
  g->category = mjCAT_DECOR;
  g->emission = emission;
  g->specular = 0.0f;
  g->reflectance = 0.0f;
}

void add_line(mjvScene* scn, const Eigen::Vector2d& a_mm, const Eigen::Vector2d& b_mm, double z,
              const std::array<float, 4>& rgba, double width_px) {
  mjvGeom* g = next_geom(scn);
  if (!g) return;
  init_decor(g, mjGEOM_LINE, nullptr, nullptr, rgba.data(), 1.0f);
  mjv_makeConnector(g, mjGEOM_LINE, width_px, a_mm.x() * kMetresPerMm, a_mm.y() * kMetresPerMm, z,
                    b_mm.x() * kMetresPerMm, b_mm.y() * kMetresPerMm, z);
}

std::array<float, 4> lighter(const std::array<float, 3>& c, float w) {
  return {c[0] + (1 - c[0]) * w, c[1] + (1 - c[1]) * w, c[2] + (1 - c[2]) * w, 1.0f};
}

}  // namespace

std::string distance_text(double mm) {
  if (!std::isfinite(mm)) return "-";
  if (mm != 0.0 && std::abs(mm) < kLeastMm) return "< 0.001 um";  // 3 digits of 1e-11 um say nothing
  const std::string um = report::sig(mm * 1000.0, 3);
  if (std::abs(std::stod(um)) < 1000.0) return um + " um";  // 999.6 um rounds to 1000: mm
  return report::sig(mm, 3) + " mm";
}

OverlayPainter::OverlayPainter(const Robot& actual, const sim::TrajectoryLog& log, double spacing_mm,
                               double marker_radius_mm, double line_px, ErrorArrow arrow)
    : actual_(actual), marker_radius_m_(marker_radius_mm * kMetresPerMm), line_px_(line_px), arrow_(arrow) {
  std::vector<Eigen::Vector2d> desired;
  std::vector<std::pair<double, Eigen::Vector2d>> trace;
  desired.reserve(log.rows.size());
  trace.reserve(log.rows.size());
  for (const sim::LogRow& r : log.rows) {
    desired.push_back(r.desired);
    trace.emplace_back(r.t, r.actual);
  }
  desired_ = thin(desired, spacing_mm, [](const Eigen::Vector2d& p) { return p; });
  trace_ = thin(trace, spacing_mm, [](const std::pair<double, Eigen::Vector2d>& p) { return p.second; });
}

void OverlayPainter::paint_model(mjModel* m) {
  for (int i = 0; i < 3; ++i) {
    const auto& c = OverlayStyle::kChainRgb[static_cast<size_t>(i)];
    const std::array<float, 4> active = {c[0], c[1], c[2], 1.0f};
    const std::array<float, 4> passive = lighter(c, 0.45f);
    const int ga = mj_name2id(m, mjOBJ_GEOM, fmt::format("geom_a{}", i + 1).c_str());
    const int gb = mj_name2id(m, mjOBJ_GEOM, fmt::format("geom_b{}", i + 1).c_str());
    if (ga >= 0) std::copy(active.begin(), active.end(), m->geom_rgba + 4 * ga);
    if (gb >= 0) std::copy(passive.begin(), passive.end(), m->geom_rgba + 4 * gb);
  }
  const int ge = mj_name2id(m, mjOBJ_GEOM, "geom_ee");
  const std::array<float, 4> hub = {0.30f, 0.30f, 0.33f, 1.0f};
  if (ge >= 0) std::copy(hub.begin(), hub.end(), m->geom_rgba + 4 * ge);
}

int OverlayPainter::max_geoms() const {
  return 1 + 3 + 1 + static_cast<int>(desired_.size() + trace_.size()) + 2 + 3;
}

void OverlayPainter::add_geoms(mjvScene* scn, double t, const sim::LogRow& row) const {
  const Geometry& g = actual_.geometry;
  // Floor: a dark slab under the whole workspace.
  {
    Eigen::Vector2d lo = g.A(0), hi = g.A(0);
    for (int i = 1; i < 3; ++i) {
      lo = lo.cwiseMin(g.A(i));
      hi = hi.cwiseMax(g.A(i));
    }
    const double reach = std::max({g.la_(0), g.la_(1), g.la_(2)}) + 400.0;
    const Eigen::Vector2d c = 0.5 * (lo + hi);
    const Eigen::Vector2d half = 0.5 * (hi - lo) + Eigen::Vector2d::Constant(reach);
    const mjtNum size[3] = {half.x() * kMetresPerMm, half.y() * kMetresPerMm, 0.005};
    const mjtNum pos[3] = {c.x() * kMetresPerMm, c.y() * kMetresPerMm, OverlayStyle::kFloorTopZ_m - 0.005};
    if (mjvGeom* f = next_geom(scn)) init_decor(f, mjGEOM_BOX, size, pos, kFloorRgba.data(), 0.0f);
  }
  // Base joints A1..A3 in their chain's colour.
  for (int i = 0; i < 3; ++i) {
    const auto& c = OverlayStyle::kChainRgb[static_cast<size_t>(i)];
    const std::array<float, 4> rgba = {0.6f * c[0], 0.6f * c[1], 0.6f * c[2], 1.0f};
    const mjtNum size[3] = {kBaseRadius_m, kBaseRadius_m, kBaseHalfHeight_m};
    const mjtNum pos[3] = {g.A(i).x() * kMetresPerMm, g.A(i).y() * kMetresPerMm, -kBaseHalfHeight_m};
    if (mjvGeom* b = next_geom(scn)) init_decor(b, mjGEOM_CYLINDER, size, pos, rgba.data(), 0.0f);
  }
  // Desired path (the whole run) and the trace travelled so far.
  for (size_t k = 1; k < desired_.size(); ++k)
    add_line(scn, desired_[k - 1], desired_[k], OverlayStyle::kPathZ_m, OverlayStyle::kDesiredRgba, line_px_);
  const double trace_z = OverlayStyle::kPathZ_m + 0.001;
  size_t k = 1;
  for (; k < trace_.size() && trace_[k].first <= t + kSameTime_s; ++k)
    add_line(scn, trace_[k - 1].second, trace_[k].second, trace_z, OverlayStyle::kTraceRgba, line_px_);
  if (!trace_.empty() && trace_[k - 1].first <= t + kSameTime_s)
    add_line(scn, trace_[k - 1].second, row.actual, trace_z, OverlayStyle::kTraceRgba, line_px_);
  add_error_arrow(scn, row);
  // End-effector marker at the true position (the last geom).
  const mjtNum size[3] = {marker_radius_m_, marker_radius_m_, kMarkerHalfHeight_m};
  const mjtNum pos[3] = {row.actual.x() * kMetresPerMm, row.actual.y() * kMetresPerMm,
                         OverlayStyle::kMarkerTopZ_m - kMarkerHalfHeight_m};
  if (mjvGeom* mk = next_geom(scn)) {
    init_decor(mk, mjGEOM_CYLINDER, size, pos, OverlayStyle::kMarkerRgba.data(), 0.0f);
    // Put the top face at kMarkerTopZ_m with the half-height the geom really has.
    mk->pos[2] = static_cast<float>(OverlayStyle::kMarkerTopZ_m - mk->size[2]);
  }
}

void OverlayPainter::add_error_arrow(mjvScene* scn, const sim::LogRow& row) const {
  const Eigen::Vector2d shaft = arrow_.gain * (row.actual - row.desired);
  const double len = shaft.norm();
  if (!(arrow_.gain > 0) || !(len > 0)) return;
  const Eigen::Vector2d tip = row.desired + shaft;
  // The head: two barbs at +-30 degrees, at most 40 % of the shaft.
  const double head = std::min(arrow_.head_mm, 0.4 * len);
  const Eigen::Vector2d back = -shaft / len * head;
  const Eigen::Vector2d side(-back.y(), back.x());
  const double c = std::cos(kBarbRad), s = std::sin(kBarbRad);
  add_line(scn, row.desired, tip, OverlayStyle::kErrorZ_m, OverlayStyle::kErrorRgba, 1.5 * line_px_);
  add_line(scn, tip, tip + c * back + s * side, OverlayStyle::kErrorZ_m, OverlayStyle::kErrorRgba, 1.5 * line_px_);
  add_line(scn, tip, tip + c * back - s * side, OverlayStyle::kErrorZ_m, OverlayStyle::kErrorRgba, 1.5 * line_px_);
}

std::array<std::string, 2> OverlayPainter::text(const sim::LogRow& row, double t0, double gain) {
  const std::string arrow = gain > 0 ? fmt::format("x{:.0f}", gain) : "none";
  return {"time\nerror\narrow\nenc 1\nenc 2\nenc 3",
          fmt::format("{:.3f} s\n{}\n{}\n{:.5f} rad\n{:.5f} rad\n{:.5f} rad", row.t - t0,
                      distance_text((row.actual - row.desired).norm()), arrow, row.readings[0], row.readings[1],
                      row.readings[2])};
}

}  // namespace gpm::render
