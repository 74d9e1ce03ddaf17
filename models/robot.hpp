// The robot model (constant during a run): geometry, home, elbow branches and
// the safety margins of its workspace. Mutable state lives elsewhere.
#pragma once

#include <array>
#include <string>

#include <Eigen/Core>

#include "models/parameters.hpp"

namespace gpm {

// Elbow branch of one chain: the active link lies counter-clockwise (+1) or
// clockwise (-1) of the line A_i -> O (DESIGN.md; default +1 for all chains).
using Branches = std::array<int, kNumChains>;

// Workspace margins used by reachability and singularity checks.
struct Limits {
  // Distance (mm) a target must keep from both edges of each chain's annulus
  // |la - lb| <= |A_i O| <= la + lb.
  double reach_margin = 2.0;
  // Type-1 (serial) singularity: each |sin(theta_a - theta_b)| must stay above.
  double min_transmission = 0.15;
  // Type-2 (parallel) singularity: smallest singular value of the three passive
  // link directions, normalised to 1 for directions 120 degrees apart.
  double min_direct = 0.15;

  bool operator==(const Limits&) const = default;
};

struct Robot {
  std::string name = "GPM2002";
  Geometry geometry = Geometry::gpm2002_nominal();
  Eigen::Vector2d home{216.5, 250.0};
  Branches branch{+1, +1, +1};
  Limits limits;

  bool operator==(const Robot&) const = default;
};

}  // namespace gpm
