// Identifiability of a choice of free parameters from given readings: SVD of
// the column-scaled Jacobian of the ML residual (one row per sample,
// calib/residuals.hpp). LM checks it at the start point before solving, the
// global solvers at the point they found, `gpm compare` at the true values.
//
// Why the ML residual for every cost: it is invariant under the similarity
// gauge (translation, rotation, scale of the whole mechanism, docs/EQUATIONS.md) at every
// point, so an unobservable direction shows as an exact zero singular value
// even far from the solution; the J1/J2/J3 residuals are invariant only where
// they vanish. J3's l_ac, l_as are a local reparameterisation of l_a, dth and
// have the same rank.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "calib/problem.hpp"

namespace gpm::calib {

// The one rank tolerance of the project: a singular value of the column-scaled
// Jacobian below kRankTolerance * (largest) counts as zero. Exact gauge
// directions measure ~2e-16 in double precision (tests/calib/test_identifiability);
// 30 samples on a straight line (practically but not exactly unidentifiable,
// docs/EQUATIONS.md) ~7e-12, which is full rank with a poor-conditioning
// warning. Because the ML residual is gauge invariant at every point, the
// tolerance holds away from the solution too (a global solver's end point).
inline constexpr double kRankTolerance = 1e-13;

// Condition numbers (largest / smallest singular value of the column-scaled
// Jacobian) above this get a "poorly exciting samples" warning. Samples spread
// over a disc of radius 80 mm around home give about 6e3 with the default
// gauge; 30 samples on a line about 1.5e11.
inline constexpr double kPoorConditioning = 1e6;

struct Identifiability {
  std::vector<int> free_index;       // parameter index of each column
  int free_count = 0;                // free_index.size()
  Eigen::VectorXd singular_values;   // of the column-scaled Jacobian, descending
  int rank = 0;
  double condition_number = 0.0;     // sigma_max / sigma_min (inf when rank-deficient)
  // Null directions in parameter units (one column each, rows as free_index),
  // unit length in the scaled metric.
  Eigen::MatrixXd null_vectors;
  std::string description;  // the unobservable direction(s) in words; empty when full rank
  std::string advice;       // which coordinate(s) to fix; empty when full rank
  // One sentence: "rank r of p: " and either "all free parameters identifiable
  // (condition number c)" or the description and the advice.
  std::string diagnosis;
};

// The four generators of the similarity gauge at geometry g as columns of a
// 15x4 matrix: translation along x, along y, rotation about A1 (bases turn,
// all offsets shift by the same angle), scale about A1 (bases and all
// lengths grow in proportion). Each leaves every ML residual unchanged.
Eigen::Matrix<double, kNumParams, 4> gauge_generators(const Geometry& g);

// Jacobian (n x 15) of the ML residuals of readings theta_m at geometry g.
Eigen::MatrixXd ml_jacobian(const std::vector<Eigen::Vector3d>& theta_m, const Geometry& g);

// Rank, conditioning and null directions of the free set at geometry g.
Identifiability analyse_identifiability(const std::vector<Eigen::Vector3d>& theta_m,
                                        const Geometry& g, const FreeMask& free);

// Throws InputError (naming --fix, the free set, the unobservable directions
// and the advice) when id shows fewer identifiable directions than free has.
void require_identifiable(const Identifiability& id, const FreeMask& free);

}  // namespace gpm::calib
