// Sampling on the fly (sim/moving_sampling.hpp).
#include "sim/moving_sampling.hpp"

#include <cmath>
#include <stdexcept>

namespace gpm::sim {

std::vector<SampleRecord> sample_along(Session& s, const WaypointPath& path, int every, long first_id) {
  if (every < 1) throw std::invalid_argument("sample_along: every must be >= 1");
  const double period = s.model.timestep_s() * s.model.steps_per_tick();
  const long ticks = std::max(1L, std::lround(waypoint_duration(path) / period));
  std::vector<SampleRecord> out;
  out.reserve(static_cast<std::size_t>(ticks / every + 1));
  for (long k = 0; k <= ticks; ++k) {
    PathPoint desired;
    waypoint_at(path, k * period, desired.p, desired.v);
    const TwinSnapshot snap = advance(s, desired);
    if (k % every != 0) continue;
    SampleRecord rec;
    rec.id = first_id + static_cast<long>(out.size());
    rec.target = desired.p;
    rec.theta_m = snap.readings;
    rec.theta_a = snap.theta_a;
    rec.xy_mm = snap.ee_mm;
    rec.tau = snap.torque;
    rec.omega = snap.velocity;
    rec.settled = false;
    out.push_back(rec);
  }
  return out;
}

}  // namespace gpm::sim
