// Changes of the actual mechanism during a run (sim/events.hpp).
#include "sim/events.hpp"

#include <algorithm>

namespace gpm::sim {

Geometry geometry_at(const Geometry& g0, const std::vector<GeometryEvent>& events, double t_s) {
  Geometry g = g0;
  for (const GeometryEvent& e : events) {
    if (t_s < e.at_s) continue;
    for (int k = 0; k < kNumParams; ++k) {
      const double d = e.delta[static_cast<std::size_t>(k)];
      if (d == 0.0) continue;
      const double span = e.over_s > 0.0 ? e.over_s : (is_offset(k) ? 0.0 : kStepRampS);
      const double f = span > 0.0 ? std::clamp((t_s - e.at_s) / span, 0.0, 1.0) : 1.0;
      g.values[static_cast<std::size_t>(k)] += f * d;
    }
  }
  return g;
}

Geometry geometry_after(const Geometry& g0, const std::vector<GeometryEvent>& events) {
  Geometry g = g0;
  for (const GeometryEvent& e : events)
    for (int k = 0; k < kNumParams; ++k) g.values[static_cast<std::size_t>(k)] += e.delta[static_cast<std::size_t>(k)];
  return g;
}

}  // namespace gpm::sim
