// Table 1 of the paper (section 2.5): the section-2.4 zero-offset search
// (projected tracking error, eq. 12-19; hw/procedures/zero_offset_search.hpp)
// run three times on the MuJoCo twin through the hardware interface, from
// three starting points chosen so that the initial offset errors are the
// paper's (its printed initial estimates minus the mean of its results).
#pragma once

#include <array>
#include <functional>

#include <Eigen/Core>

#include "models/robot.hpp"
#include "run/paper/paper_table.hpp"

namespace gpm::paper {

// The twin's actual encoder offsets in Table 1 (rad): the real robot's are
// unknown, so the table compares errors against the twin's truth with the
// paper's results against their own mean.
inline const Eigen::Vector3d kTable1TwinOffsets{0.012, -0.008, 0.006};

// Where the robot must stand for the step-2 offsets to be off by `error`
// (rad, per joint): the radical centre of IK(model, home) - error
// (eq. 32-33), the feasible pose nearest to those three angles.
Eigen::Vector2d start_for_initial_error(const Robot& model, const Eigen::Vector3d& error);

// The search's settings that set its length (paper section 2.5: 24-point
// circle here, d from 4 mm down to 0.125 mm).
struct Table1Settings {
  int circle_points = 24;
  double d_min_mm = 0.125;
  std::function<void(int experiment)> on_experiment;  // called as experiment 1, 2, 3 starts (optional)
};

// Runs the three searches (about 10 s of wall time each) and builds Table 1.
// Throws what the hardware throws when the twin cannot be built or a search stops.
Table table1(const Table1Settings& settings = {});

}  // namespace gpm::paper
