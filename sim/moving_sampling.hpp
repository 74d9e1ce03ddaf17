// Samples taken on the fly: the twin follows a continuous excitation path
// (sim/waypoint_path.hpp) at the drive loop rate, and every `every`-th loop
// instant becomes one sample: the three readings latched at that instant with
// the true state, drive torques and joint speeds of the same instant, and the
// torques the drives applied before it (SampleRecord::tau_last, tau_between). No
// averaging: the motion dithers the encoders' quantisation, so thousands of
// instantaneous readings at distinct configurations carry more information
// than a few averaged ones at rest.
#pragma once

#include <vector>

#include "sim/sampling.hpp"
#include "sim/waypoint_path.hpp"

namespace gpm::sim {

// Follows path from its start (the twin should be there, at rest) and returns
// one sample per `every` drive loop periods (every >= 1), ids from first_id;
// target is the desired point of that instant, settled is false (in motion).
// A tracking stop (TrackingStop of advance()) carries the samples taken before it.
std::vector<SampleRecord> sample_along(Session& s, const WaypointPath& path, int every, long first_id);

}  // namespace gpm::sim
