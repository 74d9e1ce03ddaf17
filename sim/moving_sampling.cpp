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
  // Drive torques of the periods since the last sample (applied before the next sample's instant).
  Eigen::Vector3d sum_between = Eigen::Vector3d::Zero();
  Eigen::Vector3d last_torque = Eigen::Vector3d::Zero();
  long periods_between = 0;
  for (long k = 0; k <= ticks; ++k) {
    PathPoint desired;
    waypoint_at(path, k * period, desired.p, desired.v);
    TwinSnapshot snap;
    try {
      snap = advance(s, desired);
    } catch (TrackingStop& stop) {  // the samples taken so far are kept
      stop.samples = std::move(out);
      throw;
    }
    if (k % every != 0) {
      sum_between += snap.torque;
      last_torque = snap.torque;
      ++periods_between;
      continue;
    }
    SampleRecord rec;
    rec.id = first_id + static_cast<long>(out.size());
    rec.target = desired.p;
    rec.theta_m = snap.readings;
    rec.theta_a = snap.theta_a;
    rec.xy_mm = snap.ee_mm;
    rec.tau = snap.torque;
    rec.omega = snap.velocity;
    rec.tau_last = periods_between > 0 ? last_torque : snap.torque;
    rec.tau_between = periods_between > 0 ? Eigen::Vector3d(sum_between / static_cast<double>(periods_between)) : snap.torque;
    rec.settled = false;
    out.push_back(rec);
    sum_between = snap.torque;  // the sample's own period is the first of the next interval
    periods_between = 1;
    last_torque = snap.torque;
  }
  return out;
}

}  // namespace gpm::sim
