// Simulated calibration data of paper section 4.4: the Table 5 "actual"
// mechanism and encoder readings of random reachable workspace points.
#pragma once

#include <cstdint>

#include "calib/problem.hpp"
#include "models/robot.hpp"
#include "models/samples.hpp"

namespace gpm::calib::global {

// Paper Table 5 "actual values": ya2 0.3, xa3 433.5, ya3 499.4, la 244.1,
// 244.2, 243.5, lb 243.8, 244.2, 244.6, dth 0.01, -0.01, 0.01 (mm, rad);
// xa1, ya1, xa2 at nominal (fixed in section 4.4).
Geometry table5_actual();

// n samples at end-effector points drawn uniformly in the bounding box of the
// base joints and kept when check_reach(robot) accepts them; readings are the
// exact encoder values theta_a - dth (eq. 35) of robot.geometry's IK on
// robot.branch, with x, y filled in. The same seed gives the same samples.
// Throws InputError when n < 1 or too few points are reachable.
Samples workspace_samples(const Robot& robot, int n, uint64_t seed);

// Section 4.4's free set: xa1, ya1, xa2 fixed, the other 12 free (rank 11:
// the similarity family of ERRATA remains).
FreeMask paper_free_mask();

// The calibration problem of readings s for the Table 5 mechanism: free
// parameters start at the GPM2002 nominal values, fixed ones at their actual
// (true) values, as ERRATA requires.
Problem table5_problem(const Samples& s, const FreeMask& free);

}  // namespace gpm::calib::global
