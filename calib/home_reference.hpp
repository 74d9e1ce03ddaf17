// The encoder offsets stated at the home pose. A robot is zeroed at home: the
// offset dth_i is what makes reading + dth_i the link's angle there. The
// motion fit estimates the reducer's errors (the drive-train harmonic twice
// per motor revolution: a harmonic drive's wave generator flexes the spline
// twice a turn; and, where the data hold it, the error once per joint
// revolution: the gears' run-out) as sinusoids of mean 0, so their value at
// home sits in the fit's dth_i. Moving it out (dth_i less the error at the
// home reading, the error referenced to 0 there) gives the same link angle at
// every reading and the offsets at home (docs/MOTION_MODEL.md, "Offsets at
// home").
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "calib/motion_correction.hpp"
#include "calib/problem.hpp"
#include "calib/reading_model.hpp"
#include "models/robot.hpp"

namespace gpm::calib {

// A robot's home pose (mm) and the elbow branches its chains take there.
struct HomePose {
  Eigen::Vector2d p = Eigen::Vector2d::Zero();
  Branches branch{+1, +1, +1};
};

// The readings (rad) geometry g commands at home (eq. 31, 35); nullopt where a chain cannot reach it.
std::optional<Eigen::Vector3d> home_readings(const Geometry& g, const HomePose& home);

// The reducer's errors a fit estimated, per harmonic order (a1 a2 a3 b1 b2
// b3, rad, and their 1-sigma; 0 and NaN where not estimated or not the
// reducer's: referenced_at_home): twice per motor revolution from
// fit.harmonic, once per joint revolution from fit.cyclic where model
// estimates it as the reducer's (estimates_reducer_joint_error).
struct ReducerErrors {
  std::array<std::array<double, 6>, kHarmonicOrders> h{};
  std::array<std::array<double, 6>, kHarmonicOrders> sigma{};
};
ReducerErrors reducer_errors(const MotionFit& fit, const MotionModel& model);

// e_i(theta_m) = sum over the orders o of a_oi sin(k_o theta_m) + b_oi
// cos(k_o theta_m) (rad; k_o: harmonic_angle): the reducer's error of joint
// i (0..2) at gear ratio N.
double reducer_error(const ReducerErrors& e, int i, double theta_m, double gear_ratio);

// What offsets_at_home moved: the home readings and e_i there (rad).
struct HomeOffsets {
  Eigen::Vector3d reading = Eigen::Vector3d::Zero();
  Eigen::Vector3d moved_rad = Eigen::Vector3d::Zero();
};

// Moves the reducer's errors e (reducer_errors of the fit) at the home
// readings of result's geometry out of result's dth_i (dth_i - e_i(r_home_i)),
// adds the variance of e_i(r_home_i) (from e.sigma, the coefficients'
// correlations neglected) to dth_i's, and shifts the readings `used` (those
// the fit explains, corrected by the errors of mean 0) by +e_i(r_home_i), so
// they stand for the same link angles with the new offsets; reading (its
// harmonics e's) is referenced at home (ReadingModel::reducer_home_rad).
// nullopt, nothing changed, where e is all 0 or the geometry cannot reach home.
std::optional<HomeOffsets> offsets_at_home(const HomePose& home, const ReducerErrors& e, double gear_ratio,
                                           Result& result, std::vector<Eigen::Vector3d>& used,
                                           ReadingModel* reading);

// The note of what offsets_at_home moved.
std::string offsets_at_home_note(const HomeOffsets& moved);

}  // namespace gpm::calib
