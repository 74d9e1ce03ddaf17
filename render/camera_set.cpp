#include "render/camera_set.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "models/errors.hpp"
#include "models/mjcf.hpp"

namespace gpm::render {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTopElevationDeg = -90.0;
constexpr double kTopAzimuthDeg = 90.0;  // image up = +Y, image right = +X
constexpr double kObliqueElevationDeg = -40.0;
constexpr double kObliqueAzimuthDeg = 90.0;
constexpr double kObliqueDistanceFactor = 1.15;

// Distance at which a pinhole of vertical field fovy_deg sees the whole region.
double fit_distance(const Framing& f, double fovy_deg, double aspect) {
  const double half_w = 0.5 * (f.hi.x() - f.lo.x()) * kMetresPerMm;
  const double half_h = 0.5 * (f.hi.y() - f.lo.y()) * kMetresPerMm;
  const double t = std::tan(0.5 * fovy_deg * kPi / 180.0);
  return std::max(half_h / t, half_w / (aspect * t));
}

}  // namespace

std::vector<std::string> camera_names(const mjModel* m) {
  std::vector<std::string> names = {"top", "oblique"};
  for (int i = 0; i < m->ncam; ++i) {
    const char* n = mj_id2name(m, mjOBJ_CAMERA, i);
    if (n && *n) names.emplace_back(n);
  }
  return names;
}

void check_camera(const mjModel* m, const std::string& name, const std::string& what) {
  const std::vector<std::string> names = camera_names(m);
  if (std::find(names.begin(), names.end(), name) != names.end()) return;
  throw InputError(fmt::format("{}: unknown camera '{}' (valid: {})", what, name, fmt::join(names, ", ")));
}

mjvCamera make_camera(const mjModel* m, const std::string& name, const Framing& f, double aspect) {
  check_camera(m, name, "camera");
  mjvCamera cam;
  mjv_defaultCamera(&cam);
  if (name == "top" || name == "oblique") {
    const Framing region = f.empty() ? Framing{{0, 0}, {1, 1}} : f;
    cam.type = mjCAMERA_FREE;
    cam.lookat[0] = 0.5 * (region.lo.x() + region.hi.x()) * kMetresPerMm;
    cam.lookat[1] = 0.5 * (region.lo.y() + region.hi.y()) * kMetresPerMm;
    cam.lookat[2] = 0.0;
    cam.distance = fit_distance(region, m->vis.global.fovy, aspect);
    if (name == "top") {
      cam.elevation = kTopElevationDeg;
      cam.azimuth = kTopAzimuthDeg;
    } else {
      cam.elevation = kObliqueElevationDeg;
      cam.azimuth = kObliqueAzimuthDeg;
      cam.distance *= kObliqueDistanceFactor;
    }
    return cam;
  }
  cam.type = mjCAMERA_FIXED;
  cam.fixedcamid = mj_name2id(m, mjOBJ_CAMERA, name.c_str());
  return cam;
}

}  // namespace gpm::render
