// The first samples of a path sampled on the fly (the offsets stage,
// sampling.offsets_first_s, or a pass that ended early because the robot
// left its plan by the readings, hw/procedures/trajectory_session.hpp) tell
// where the encoders' zeros are. The path planned again with them stays near
// its plan, where the data sheet's offsets took it away (the offsets, 0.01
// rad on a 244 mm link, are most of a robot's deviation from its plan near
// the drives' singular poses).
#pragma once

#include <array>
#include <vector>

#include "models/drive_margin.hpp"
#include "models/parameters.hpp"
#include "sim/sampling.hpp"

namespace gpm::scenario {

// Fewer samples than this: no estimate (kept samples of a path that ended at once).
inline constexpr int kMinFirstPassSamples = 12;

// The encoder offsets the samples show with the rest of the geometry as
// uncertain as stated (calib/geometry_filter.hpp: prior the stated geometry
// with 1-sigma `prior`, one sample per 10 ms of their t_s): the stated
// geometry with dth1..3 replaced by the estimate's, and their 1-sigma.
struct OffsetsEstimate {
  Geometry geometry;
  std::array<double, 3> sigma_rad{};
};

// The offsets estimate of `samples` (taken on the fly, t_s increasing) about
// `stated`; throws InputError with fewer than kMinFirstPassSamples samples.
OffsetsEstimate offsets_learnt(const Geometry& stated, const std::vector<sim::SampleRecord>& samples,
                               const ModelTolerance& prior);

}  // namespace gpm::scenario
