// Fisher information and Cramer-Rao bounds of candidate calibration poses,
// evaluated at a known (nominal) geometry: the information a pose would give
// if the robot were exactly that geometry. This is what is known before
// calibration, so excitation design is done at the nominal geometry.
//
// Model (paper section 3.1, docs/EQUATIONS.md; calib/crb.hpp): each pose j gives one
// scalar ML residual r_j = P_j / |dP_j/d theta_m| (calib/residuals.hpp) that is
// N(0, sigma^2) under iid encoder noise sigma. With g_j = d r_j / d params (the
// free columns of its gradient at the noiseless readings of pose j), the
// Fisher information of n poses is
//   F = (1 / sigma^2) sum_j g_j g_j'
// and the Cramer-Rao bound on any unbiased estimate of the free parameters is
// C = F^-1, parameter k's bound sigma_k = sqrt(C_kk).
//
// Scaled bounds (to compare mm and rad fairly): a length or base coordinate
// keeps its mm; an encoder offset dth_i is multiplied by the active link
// length la_i (mm), the displacement of elbow B_i that an offset error of
// dth_i causes (eq. 30, 35). "worst" is the largest scaled bound, "mean" the
// mean of the scaled bounds over the free parameters.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "models/parameters.hpp"
#include "models/robot.hpp"

namespace gpm::calib::excitation {

// Information rows of poses at the robot's geometry: row j is g_j' (unit
// noise), columns the free parameters in index order. Throws InputError for a
// pose the robot cannot reach (inverse kinematics) or a degenerate one.
Eigen::MatrixXd information_rows(const Robot& robot, const FreeMask& free,
                                 const std::vector<Eigen::Vector2d>& poses);

// F = rows' rows / sigma^2 (sigma in rad, > 0).
Eigen::MatrixXd fisher_information(const Eigen::MatrixXd& rows, double sigma);

// Per free parameter (index order): 1 for mm parameters, la_i for dth_i.
Eigen::VectorXd parameter_scale(const Geometry& g, const FreeMask& free);

// Cramer-Rao bounds of a set of poses, per free parameter and summarised.
struct Bounds {
  std::vector<int> free_index;  // parameter index of each entry
  Eigen::VectorXd sigma;        // sqrt(C_kk), own units (mm or rad); +inf if singular
  Eigen::VectorXd scaled;       // sigma times parameter_scale (mm)
  double worst_mm = 0.0;        // max of scaled
  int worst_param = -1;         // parameter index of the max
  double mean_mm = 0.0;         // mean of scaled
  double log_det = 0.0;         // log det F (-inf if singular)
};

// Bounds from information rows (unit noise) and the noise sigma (rad).
Bounds bounds_from_rows(const Eigen::MatrixXd& rows, const Geometry& g, const FreeMask& free,
                        double sigma);

// Bounds of poses at the robot's geometry (information_rows + bounds_from_rows).
Bounds pose_bounds(const Robot& robot, const FreeMask& free,
                   const std::vector<Eigen::Vector2d>& poses, double sigma);

}  // namespace gpm::calib::excitation
