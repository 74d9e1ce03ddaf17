// Which of a geared drive's reading effects a robot's data need, per joint
// (calib/motion_correction.hpp MotionModel: backlash, the harmonic errors
// once per joint revolution and once and twice per motor revolution, the
// motor's cogging, hysteresis): a
// backward selection by Wald tests. The calibration in motion is fitted with
// every candidate the data excite; a backlash is kept where its estimate lies
// k 1-sigma of the noise model (MotionFit::noise_sigma) from 0, a harmonic where its pair (a, b) does at the same level
// (a^2/sa^2 + b^2/sb^2 >= the chi-square(2) quantile of the two-sided k-sigma
// level); the fit is made again with the kept ones. A backlash is a
// candidate only where the samples can tell its flank (the mesh torque above
// MotionModel::backlash_torque_min_Nm in half the samples, and for all such
// joints together in a quarter of them; else it is reported as dropped). The hysteresis,
// nonlinear in its loss, comes after the others, on the model they chose:
// a candidate where the mesh torque spans 4 thresholds at the fit's start,
// kept where its loss lies k 1-sigma above 0 and the fit with it lowers
// the chi-square by more than ln n per joint (BIC). A robot's data sheet says
// what its reducer may do; what this robot does is what its readings show.
#pragma once

#include <string>
#include <vector>

#include "calib/motion_correction.hpp"

namespace gpm::calib {

struct DriveEffectSelection {
  MotionFit fit;                     // the fit with the kept effects
  MotionModel model;                 // model with the kept effects switched on
  std::vector<std::string> kept;     // e.g. "backlash 2 (12.3 sigma)"
  std::vector<std::string> dropped;  // e.g. "motor harmonic 1 of joint 3 (1.2 sigma)"
};

// model with the harmonic candidates of candidates switched on as well (the
// errors once per joint revolution, once and twice per motor revolution).
MotionModel with_harmonic_candidates(MotionModel model, const MotionModel& candidates);

// The level a pair (a, b) of estimates must reach, sqrt(a^2/sa^2 + b^2/sb^2),
// to lie k sigma from 0 as one value two-sided would: chi-square(2) above
// -2 ln(erfc(k / sqrt 2)).
double pair_sigma_level(double k);

// Fits problem with model plus every candidate in candidates (the effects
// switched on there), then again with those the Wald test at k sigma keeps
// (calibrate_in_motion: omega, tau, alpha as there); when it keeps none and
// fit_of_model is given (the fit of model, already made), that fit is taken
// instead of being made again. Where the fit with the candidates diverges
// (its corrected readings fit no robot), none is kept and the fit of model
// is taken (a note in dropped). Throws as calibrate_in_motion on model.
DriveEffectSelection select_drive_effects(const Problem& problem, const std::vector<Eigen::Vector3d>& omega,
                                          const std::vector<Eigen::Vector3d>& tau, const LmOptions& options,
                                          const MotionModel& model, const std::vector<Eigen::Vector3d>& alpha,
                                          const MotionModel& candidates, double k = 3.0,
                                          const MotionFit* fit_of_model = nullptr);

}  // namespace gpm::calib
