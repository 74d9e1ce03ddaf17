// The cameras a video can be taken with: `top` (straight down, +X right, +Y
// up; the default), `oblique` (from the -Y side, 40 degrees down) and every
// camera defined in the model, by name. Free cameras frame a region of the
// plane so that all of it is in view.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <mujoco/mujoco.h>

namespace gpm::render {

// Axis-aligned region of the plane (mm) a free camera must show.
struct Framing {
  Eigen::Vector2d lo{1e300, 1e300};
  Eigen::Vector2d hi{-1e300, -1e300};
  // Grows the region to contain p (mm).
  void include(const Eigen::Vector2d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  bool empty() const { return lo.x() > hi.x(); }
};

// Camera names valid for model m: "top", "oblique", then the model's cameras.
std::vector<std::string> camera_names(const mjModel* m);

// Throws InputError "WHAT: unknown camera 'NAME' (valid: top, oblique, ...)"
// unless name is one of camera_names(m).
void check_camera(const mjModel* m, const std::string& name, const std::string& what);

// The MuJoCo camera called name, framing region f in a viewport of the given
// width/height aspect (free cameras), or the model's fixed camera of that
// name. Throws InputError as check_camera.
mjvCamera make_camera(const mjModel* m, const std::string& name, const Framing& f, double aspect);

}  // namespace gpm::render
