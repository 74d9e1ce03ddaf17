// Samples in which a passive link may be crossing its play.
//
// A passive link with joint clearance acts as lb_i + d_i sgn(T_i)
// (calib/passive_tension.hpp): it sits at the end of its play that its axial
// force T_i presses. When T_i changes sign the link does not jump to the
// other end: it is carried across the gap 2 d_i by the force building up
// against it, knocks into the far end and rings there. While it does, its
// length is neither lb_i - d_i nor lb_i + d_i, and a sample read then misses
// the clearance model by up to 2 d_i over la_i sin(theta_b - theta_a) in the
// reading. Such a sample's sign is left uncertain for the crossing's duration
// after the force's last sign change (calib/motion_correction.hpp,
// MotionModel::crossing_samples).
#pragma once

#include <array>
#include <optional>
#include <vector>

#include <Eigen/Core>

namespace gpm::calib {

// Per sample and chain, whether passive link i may be crossing its play: true
// for the `samples` samples from each one whose force tension[j][i] (N) has
// the other sign than the sample before (the first sample of a new sign and
// the samples - 1 after it); false elsewhere and everywhere when samples <= 0.
// A sample whose forces are unknown (nullopt) neither starts nor ends a
// crossing; one the window covers is marked all the same.
std::vector<std::array<bool, 3>> play_crossing(const std::vector<std::optional<Eigen::Vector3d>>& tension, int samples);

}  // namespace gpm::calib
