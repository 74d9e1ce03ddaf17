// Which parameters the encoder readings determine at a point: the rank of the
// Jacobian of the closure residuals and the similarity family of ERRATA.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "models/parameters.hpp"

namespace gpm::calib::global {

// Jacobian (samples x free parameters, columns in the order xa1 ... dth3) of
// the per-sample closure residual g_j = |O - B_i|^2 - lb_i^2 at the radical
// centre O (every row of E2/E3 equals g_j, ERRATA; J3 = 3 sum g_j^2).
// Analytic, by implicit differentiation of F_i(O, g) = |O - B_i|^2 - lb_i^2
// - g = 0, i = 1..3: d(O, g)/dp = -[2 (O - B_i)^T, -1]^-1 dF/dp with
// dF_i/dp = -2 (O - B_i) . dB_i/dp - 2 lb_i dlb_i/dp (eq. 30, 32-33, 35).
// Rank and singular values are the same in (la, dth) as in the decoupled
// (l_ac, l_as) of J3, which are a local change of variables.
// Rows of collinear-elbow samples are zero.
Eigen::MatrixXd closure_jacobian(const std::vector<Eigen::Vector3d>& theta_m, const Geometry& g,
                                 const FreeMask& free);

// Identifiability diagnosis of the free parameters at g.
struct Identifiability {
  int rank = 0;                      // numerical rank (sigma > 1e-9 sigma_max, columns scaled to unit norm)
  int free_count = 0;
  double condition_number = 0.0;     // sigma_max / sigma_min of the column-scaled Jacobian
  Eigen::VectorXd singular_values;   // column-scaled, descending
  // |cos| of the angle between the weakest singular direction and the
  // similarity family (scale and rotation about A1 that keeps every fixed
  // parameter); NaN when the fixed set admits no such family.
  double similarity_alignment = 0.0;
  std::string diagnosis;             // one sentence
};

// The rank, conditioning and one-sentence diagnosis of the free parameters
// of g with readings theta_m.
Identifiability closure_identifiability(const std::vector<Eigen::Vector3d>& theta_m,
                                        const Geometry& g, const FreeMask& free);

// The similarity family's direction in the 15 parameters at g: the
// combination of scaling and rotating the whole mechanism about A1 (link
// lengths scale, base joints move, offsets shift) that leaves every fixed
// parameter unchanged, normalised; all zero when only the identity does.
Eigen::Matrix<double, kNumParams, 1> similarity_direction(const Geometry& g, const FreeMask& free);

}  // namespace gpm::calib::global
