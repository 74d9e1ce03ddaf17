// Deterministic synthetic encoder samples from a known ("actual") robot, for
// tests, studies, benchmarks and `gpm compare`: end-effector poses drawn
// uniformly in a region (a disc, or the bounding box of the base joints as in
// paper section 4.4) and kept only when reachable with the robot's margins
// (gpm::check_reach); readings by IK on the robot's branches (theta_m =
// theta_a - dth, eq. 35) plus optional iid Gaussian encoder noise. Every draw
// comes from gpm::Rng (models/rng.hpp), so a seed gives the same samples with
// every compiler and standard library.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "models/robot.hpp"
#include "models/samples.hpp"

namespace gpm::calib {

// n reachable poses uniform in the disc (centre, radius), seeded. Throws
// InputError when too few points of the disc are reachable.
std::vector<Eigen::Vector2d> disc_poses(const Robot& actual, int n, const Eigen::Vector2d& centre,
                                        double radius, std::uint64_t seed);

// n reachable poses uniform in the bounding box of the three base joints
// (paper section 4.4's random workspace points), seeded. Throws InputError
// when n < 1 or too few points are reachable.
std::vector<Eigen::Vector2d> workspace_poses(const Robot& actual, int n, std::uint64_t seed);

// Samples (readings and true x,y) of actual at the given poses; readings get
// N(0, sigma^2) noise from seed when sigma > 0.
Samples samples_at(const Robot& actual, const std::vector<Eigen::Vector2d>& poses, double sigma = 0.0,
                   std::uint64_t seed = 0);

// Exact samples at workspace_poses(actual, n, seed).
Samples workspace_samples(const Robot& actual, int n, std::uint64_t seed);

}  // namespace gpm::calib
