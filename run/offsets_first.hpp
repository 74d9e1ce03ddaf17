// A path sampled on the fly that ended early (the robot left its plan by the
// readings, hw/procedures/trajectory_session.hpp) still tells where the
// encoders' zeros are: the offsets dth1..3 fitted to the samples it kept, the
// rest of the geometry as the data sheet states it. The path planned again
// with them stays near its plan, where the data sheet's offsets took it away
// (the offsets, 0.01 rad on a 244 mm link, are most of a robot's deviation
// from its plan near the drives' singular poses).
#pragma once

#include <vector>

#include "calib/problem.hpp"
#include "models/parameters.hpp"
#include "sim/sampling.hpp"

namespace gpm::scenario {

// Fewer samples than this: no fit (kept samples of a path that ended at once).
inline constexpr int kMinFirstPassSamples = 12;

// The geometry `stated` with dth1..3 fitted by Levenberg-Marquardt on the ML
// closure residual (paper eq. 1 and 35; calib/residuals.hpp) to the readings
// of `samples`, every other parameter fixed at its stated value; the result's
// 1-sigma from the residuals' spread (the model misses the drive train here).
// Throws InputError with fewer than kMinFirstPassSamples samples.
calib::Result offsets_from_samples(const Geometry& stated, const std::vector<sim::SampleRecord>& samples);

}  // namespace gpm::scenario
