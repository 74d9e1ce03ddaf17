// The drives' friction that the clearance's force signs assume, chosen by
// the model test: a profile of the calibration in motion over a common
// factor k of the stated friction.
//
// The passive links' force signs (calib/passive_tension.hpp) come from the
// drive torque less the stated motor-side friction k F_i, k b_i. A wrong
// friction gives wrong signs where the drive torque is near it, and the
// plays and the geometry fitted to those signs leave larger ML residuals.
// Each factor k of a grid is fitted (calibrate_in_motion with MotionModel::load's
// Coulomb and viscous friction times k); the factor whose fit has the
// smallest chi2 / dof of its model test (calib/model_test.hpp: ML residuals
// of the corrected readings over sigma, n - p degrees of freedom) is taken.
// On the realistic twin's main job chi2/dof against k (the twin at k = 1):
// 8.2 at 0, 1.49 at 0.5, 1.31 at 0.75, 1.43 at 1, 1.81 at 1.25, 2.8 at 1.5, 7.1 at 2.
// Given a start (ProfileStart), a profile can walk from it down chi2/dof
// along the grid to the first local minimum instead of fitting every value.
#pragma once

#include <array>
#include <limits>
#include <optional>
#include <vector>

#include "calib/motion_correction.hpp"

namespace gpm::calib {

struct FrictionProfile {
  MotionFit fit;                      // the fit at the chosen factor
  double scale = 1.0;                 // the chosen factor k (or speed v_F, friction_speed_profile)
  MotionModel model;                  // the model with the friction times k (for motion_crb)
  std::vector<double> scales;         // the factors tried, in the grid's order
  std::vector<double> chi2_per_dof;   // the model test's chi2 / dof of each (inf where the fit failed)
};

// What a profile knows before it starts, and how it searches. By default
// every value of the grid is fitted. With walk (the grid ascending) it fits
// value and its neighbours and walks on while chi2/dof falls, stopping at
// the first local minimum along the grid: the same choice as fitting every
// value wherever chi2/dof has one minimum along the grid (far from the
// stated friction, at a few times it, chi2/dof can fall again: walk from the
// stated value); if no fit of the walk succeeds, or the minimum it finds
// has a chi2/dof above trust (a model that misses the readings: its chi2/dof
// need not have one minimum along the grid), the rest is fitted.
struct ProfileStart {
  std::optional<double> value;       // a value of the grid: where a walk starts, the known fit's
  const MotionFit* known = nullptr;  // the fit at value, already made with the model there (not made again)
  bool walk = false;                 // walk from value down chi2/dof instead of fitting every value
  double trust = std::numeric_limits<double>::infinity();  // largest chi2/dof of a walk's minimum taken as it is
};

// The factors 0 (no friction) and 2^(m/2), m = -4..4 (0.25 to 4 in steps of sqrt 2).
std::vector<double> default_friction_scales();

// calibrate_in_motion at each factor of scales (>= 0) times model.load's
// friction, the fit of the smallest chi2/dof taken (reading noise sigma, rad,
// > 0). Throws InputError for no factor, a factor < 0, sigma <= 0, or when
// no factor's fit succeeds (the last fit's error), a start value that is
// not one of scales, or a walk without a start value or along scales not
// ascending.
FrictionProfile calibrate_friction_profile(const Problem& problem, const std::vector<Eigen::Vector3d>& omega,
                                           const std::vector<Eigen::Vector3d>& tau, const LmOptions& options,
                                           const MotionModel& model, const std::vector<Eigen::Vector3d>& alpha,
                                           const std::vector<double>& scales, double sigma,
                                           const ProfileStart& start = {});

// The speed v_F over which the drives' friction builds up
// (TransmissionLoad::friction_speed_rad_s), chosen by the model test as the
// factor is: calibrate_in_motion at each speed of speeds (> 0) in
// model.load, the fit of the smallest chi2/dof taken (FrictionProfile::scale
// is then the speed). A real drive's friction is not a step at zero speed
// (lubricant film, compliant seals): with the step (v_F 0.01 rad/s) the
// friction twist c_i F_i is taken in full at speeds where it is still
// building up. On the realistic twin the twist's mean against the link
// speed follows tanh(omega / 0.13 rad/s). Throws as calibrate_friction_profile
// (a speed <= 0 too).
FrictionProfile friction_speed_profile(const Problem& problem, const std::vector<Eigen::Vector3d>& omega,
                                       const std::vector<Eigen::Vector3d>& tau, const LmOptions& options,
                                       const MotionModel& model, const std::vector<Eigen::Vector3d>& alpha,
                                       const std::vector<double>& speeds, double sigma, const ProfileStart& start = {});

// The speeds 0.01 * 10^(m/2) rad/s, m = 0..4 (0.01 to 1 rad/s).
std::vector<double> default_friction_speeds();

// The largest correlation between the friction twist's column and the latch
// skew's at which a friction speed is tried: a variance inflation 1 / (1 -
// rho^2) of at most 10 for the pair.
inline constexpr double kMaxSkewCorrelation = 0.949;

// The speeds v of `speeds` whose friction twist the samples tell from the
// latch skew: on every joint i of `skewed` (those with a skew estimated) the
// correlation of tanh(omega_i / v) with omega_i over the samples (joint
// speeds omega, rad/s) is at most max_correlation. Where v is large against
// the joints' speeds the twist is linear in the speed, the skew's own column,
// and the fit trades the two (skews of milliseconds). The smallest speed
// stays where none qualifies; all stay where no joint is skewed or no joint
// moves.
std::vector<double> speeds_told_from_skew(const std::vector<double>& speeds, const std::vector<Eigen::Vector3d>& omega,
                                          const std::array<bool, 3>& skewed,
                                          double max_correlation = kMaxSkewCorrelation);

}  // namespace gpm::calib
