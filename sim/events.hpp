// Changes of the actual mechanism during a run (scenario `events:`, used by
// `gpm monitor`): a step (`change`) or a linear drift (`ramp` over `over_s`)
// added to actual parameters from `at_s` on, on top of thermal growth.
#pragma once

#include <array>
#include <vector>

#include "models/parameters.hpp"

namespace gpm::sim {

// A step of a length or base coordinate is spread over this time so that the
// mechanism never jumps (a one-step edit of the MuJoCo model leaves a gap and a
// transient): 1000 steps at the default 0.5 ms. An offset step is immediate
// (it moves the reading, not the mechanism).
inline constexpr double kStepRampS = 0.5;

struct GeometryEvent {
  double at_s = 0.0;                       // when it begins (s)
  double over_s = 0.0;                     // 0: a step; > 0: a linear drift over this time (s)
  std::array<double, kNumParams> delta{};  // change of each parameter (mm or rad)
};

// The geometry at time t: g0 plus every event's contribution so far.
Geometry geometry_at(const Geometry& g0, const std::vector<GeometryEvent>& events, double t_s);

// The geometry after every event has fully taken effect.
Geometry geometry_after(const Geometry& g0, const std::vector<GeometryEvent>& events);

}  // namespace gpm::sim
