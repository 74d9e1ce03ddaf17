// Sampling plans designed at run time (`sampling: {pattern: designed |
// trajectory, count: N}`): the poses come from the excitation design of
// calib/excitation, made on the controller's model for the calibration's free
// parameters, inside the robot's limits tightened by the design's guard.
#pragma once

#include <functional>

#include <Eigen/Core>

#include "models/parameters.hpp"
#include "sim/scenario.hpp"

namespace gpm::scenario {

// Fills scenario.sampling->poses when the plan still needs a design (no-op
// otherwise), from candidates that also pass `admissible` when given (the
// hardware's safety limits). Throws InputError, before anything moves, when
// the count (or the number of poses given to a designed or trajectory plan)
// is below the number of free parameters.
void design_sampling(sim::Scenario& scenario, const FreeMask& free, double sigma_rad,
                     const std::function<bool(const Eigen::Vector2d&)>& admissible = {});

}  // namespace gpm::scenario
