// The encoders' resolution as the readings themselves show it: readings of
// a quantised encoder lie on a lattice offset_i + k q per joint, so every gap
// between two distinct readings of a joint is a whole number of steps q. The
// smallest gap of a long series is one step (10 000 readings over 2e5 levels
// hold adjacent levels many times over); a series whose gaps are not whole
// multiples of its smallest one (averaged or noisy readings, or too few of
// them) shows no step. A geared drive's motor encoder of 2^bits counts is
// 2^bits N counts per joint revolution: the data show which.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

namespace gpm::calib {

// The quantisation step (rad) of readings theta_m: the largest of the
// joints' steps, each the smallest gap between its distinct readings when at
// least 99 % of the gaps are whole multiples of it (to 2 %) and the joint has
// at least 100 distinct readings; nullopt when some joint shows no step.
std::optional<double> reading_step(const std::vector<Eigen::Vector3d>& theta_m);

}  // namespace gpm::calib
