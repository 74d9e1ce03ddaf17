// Candidate poses for excitation design: a square grid over the workspace,
// kept where the robot reaches the pose on its branches with its margins
// (gpm::check_reach: annulus margin and both singularity margins of
// robot.limits), tightened by a guard so that a pose chosen at the nominal
// geometry stays valid on the actual mechanism, whose parameters differ by
// up to a few mm and hundredths of a radian.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "models/robot.hpp"

namespace gpm::calib::excitation {

// How much stricter than robot.limits the candidates must be.
struct Guard {
  double reach_mm = 2.0;        // added to limits.reach_margin
  double transmission = 0.02;   // added to limits.min_transmission
  double direct = 0.02;         // added to limits.min_direct
};

// The robot with its limits tightened by guard (the check every candidate passes).
Robot guarded_robot(const Robot& robot, const Guard& guard);

// Grid points (spacing step_mm, one of them at robot.home) inside the
// intersection of the three outer reach discs that pass check_reach of
// guarded_robot(robot, guard). Throws InputError when step_mm is not positive
// or nothing is reachable.
std::vector<Eigen::Vector2d> reachable_grid(const Robot& robot, double step_mm, const Guard& guard);

}  // namespace gpm::calib::excitation
