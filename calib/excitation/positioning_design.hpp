// Excitation design for the positioning a user gets (excitation.hpp,
// Criterion::kPositioning): poses whose readings tell each encoder's error
// once per joint revolution from the geometry.
//
// Such an error, a_i sin(theta_m_i) + b_i cos(theta_m_i) in reading i
// (calib/motion_correction.hpp MotionModel::cyclic_prior_rad), moves elbow
// B_i by la_i e(theta) across its link: half of it is a constant shift of the
// elbow circle, which a shifted base takes up, half a term twice per joint
// revolution, which only poses spread over the joint's range can show. Where
// the data cannot tell it, the geometry takes it up and the user's
// positioning carries it. It enters the reading as an offset does with the
// other sign (theta_a = theta_m + dth - e, models/kinematics.hpp), so with
// g_j the ML residual's gradient of pose j (fisher.hpp) its columns are
// -g_j,dth_i sin(theta_m_ij) and -g_j,dth_i cos(theta_m_ij). With n readings
// per pose of noise sigma and the data sheet's prior s on each coefficient:
//   F = (n / sigma^2) sum_j h_j h_j' + diag(0, ..., 0, 1/s^2, ..., 1/s^2),
//   h_j = (g_j, the error's six columns),  C = F^-1,
// and the criterion is the positioning RMS the geometry's block of C causes
// over the workspace disc, sqrt(trace(W C_gg)), W = positioning_weight
// (calib/positioning_error.hpp): for static poses, the Bayesian bound the run
// reports (positioning_um.bound_rms).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "calib/positioning_error.hpp"
#include "models/parameters.hpp"
#include "models/robot.hpp"

namespace gpm::calib::excitation {

// What the positioning criterion weighs.
struct PositioningPrior {
  double cyclic_prior_rad = 0.0;    // s: 1-sigma of each coefficient a_i, b_i (rad); 0: the robot's data sheet's
                                    // (DataSheet::joint_harmonic_max_rad() / sqrt 2, as the calibration's prior)
  double samples_per_pose = 100.0;  // n: readings one pose stands for (on the fly: the path near it)
  double radius_mm = 80.0;          // the disc round the robot's home where the positioning is judged
  double step_mm = 10.0;            // and its grid
};

// The criterion's constants for one robot, free set, prior and noise.
struct PositioningCriterion {
  Eigen::VectorXd column_scale;       // divides the rows' columns (conditioning only)
  Eigen::MatrixXd weight;             // W in scaled columns, zero for the error's columns (mm^2)
  Eigen::VectorXd prior_information;  // 1 / (scale s)^2 on the error's columns, 0 on the geometry's
  double row_weight = 1.0;            // sqrt(n) / sigma
};

// Information rows of poses (fisher.hpp information_rows, unit noise) with
// the six columns a_1 b_1 a_2 b_2 a_3 b_3 of the error once per joint
// revolution appended. Throws InputError unless dth_1..3 are free, or as
// information_rows does.
Eigen::MatrixXd rows_with_cyclic_error(const Robot& robot, const FreeMask& free,
                                       const std::vector<Eigen::Vector2d>& poses);

// The criterion's constants for rows of candidates (rows_with_cyclic_error)
// at robot (its nominal geometry), noise sigma (rad, > 0). Throws InputError
// for a negative prior, a data sheet stating no such error, or a sample
// count or noise that is not positive.
PositioningCriterion positioning_criterion(const Robot& robot, const FreeMask& free, const PositioningPrior& prior,
                                           double sigma, const Eigen::MatrixXd& rows);

// sqrt(trace(W C_gg)) of the chosen rows (um); +inf where F is singular.
double positioning_bound_um(const Eigen::MatrixXd& rows, const std::vector<int>& chosen,
                            const PositioningCriterion& c);

// Exchange minimising positioning_bound_um: each chosen pose in turn is
// swapped for the candidate that lowers the bound most (two rank-one updates
// per candidate), sweeping until a sweep swaps none; returns the swaps.
// chosen must give a finite bound.
int exchange_positioning(const Eigen::MatrixXd& rows, std::vector<int>& chosen, const PositioningCriterion& c,
                         int max_swaps);

}  // namespace gpm::calib::excitation
