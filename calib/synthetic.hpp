// Deterministic synthetic encoder samples from a known ("actual") robot, for
// tests, studies and benchmarks: poses drawn uniformly in a disc and kept only
// when reachable with the robot's margins (gpm::check_reach), readings by IK
// (theta_m = theta_a - dth, eq. 35) plus optional iid Gaussian encoder noise.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "models/robot.hpp"
#include "models/samples.hpp"

namespace gpm::calib {

// n reachable poses uniform in the disc (centre, radius), seeded.
std::vector<Eigen::Vector2d> disc_poses(const Robot& actual, int n, const Eigen::Vector2d& centre,
                                        double radius, std::uint64_t seed);

// Samples (readings and true x,y) of actual at the given poses; readings get
// N(0, sigma^2) noise from seed when sigma > 0.
Samples samples_at(const Robot& actual, const std::vector<Eigen::Vector2d>& poses, double sigma = 0.0,
                   std::uint64_t seed = 0);

}  // namespace gpm::calib
