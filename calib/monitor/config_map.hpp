// The monitor's configuration map (issue 31): what the learning phase saw
// of the residual, kept as a memory over the robot's configuration.
//
// A healthy drive train's reading error (transmission error periodic in the
// motor angle, encoder cyclic error, the twist and clearance of a load that
// follows the job) is, on a robot repeating its job, nearly a function of the
// configuration (the link angles) and of the direction of motion; an encoder
// slip is a step that persists at every configuration. The learning phase
// keeps each sample's link angles, the sign of each joint's speed and its ML
// residual at the estimate as learning ends; later samples are tested on their
// residual less the learnt residual at the same configuration (linear
// between the two nearest learnt samples of one pass), so the repeatable part
// of the error cancels and a step does not. A sample with no learnt sample
// within the radius (a configuration the learning phase did not visit, or
// visited moving the other way) has no map value.
// Pure arithmetic on arrays; allocation-free.
#pragma once

#include <Eigen/Core>

namespace gpm::calib::monitor {

// The learnt samples a map looks up (arrays of n, in the order learnt).
struct MapSamples {
  const double* t = nullptr;                 // time (s)
  const Eigen::Vector3d* theta = nullptr;    // link angles (rad)
  const Eigen::Vector3d* direction = nullptr;  // sign of each joint's speed (+-1, 0 when still)
  const double* r = nullptr;                 // residual (rad)
  int n = 0;
};

// How a look-up matches.
struct MapQuery {
  Eigen::Vector3d theta = Eigen::Vector3d::Zero();      // the sample's link angles (rad)
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();  // sign of each joint's speed
  double radius_rad = 0.0;     // farthest learnt configuration matched (link-angle distance)
  double pass_gap_s = 0.0;     // learnt samples further apart in time are on different passes
  double exclude_t = 0.0;      // learnt samples within exclude_halfwidth_s of exclude_t are ignored
  double exclude_halfwidth_s = -1.0;  // (the leave-one-out of the learning phase; < 0: none)
};

// The learnt residual at q's configuration: the nearest learnt sample of the
// same direction (not excluded) within the radius, interpolated linearly
// along the segment to its neighbour of the same pass onto which q projects
// (the nearer such segment); false when no learnt sample is within the
// radius. cursor (in/out) is where the search starts (the last match): the
// samples around it are searched first and the whole memory only when none
// of them matches. Allocation-free.
bool map_residual(const MapSamples& samples, const MapQuery& q, int& cursor, double& r_map);

}  // namespace gpm::calib::monitor
