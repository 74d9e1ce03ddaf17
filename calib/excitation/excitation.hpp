// Excitation design: which n calibration poses make the free parameters most
// accurate (issue 10). Pure calibration mathematics (models/ and calib/, no
// MuJoCo). Paper section 4.5 found that 50 poses on a line could not be
// calibrated while a circle about the workspace centre could; docs/EQUATIONS.md: the
// layout changes the achievable accuracy by orders of magnitude. Here the
// layout is chosen by optimal experiment design on the Cramer-Rao bound.
//
// The design is made at the NOMINAL geometry (what is known before
// calibration): the Fisher information of calib/excitation/fisher.hpp,
//   F(X) = (1/sigma^2) sum_{j in X} g_j g_j',
// of the ML residual's gradients g_j at the noiseless readings of each pose.
// Both criteria below are invariant to sigma (it scales F), so the chosen
// poses do not depend on the noise level; sigma only scales the bounds.
//
// Criteria (over designs X of n distinct candidate poses):
//   D-optimal:  maximise log det F(X)  (the volume of the confidence
//               ellipsoid shrinks; invariant to parameter units);
//   worst:      minimise max_k s_k sqrt(C_kk),  C = F(X)^-1, s_k = 1 for mm
//               parameters and la_i for dth_i (the elbow displacement an
//               offset error causes), i.e. the worst parameter's Cramer-Rao
//               bound in mm.
//   positioning: minimise the positioning RMS over the workspace disc that
//               the geometry's bound causes, each encoder's error once per
//               joint revolution estimated with it under the data sheet's
//               prior (positioning_design.hpp); unlike the others it depends
//               on sigma, through the prior's weight against the readings.
//
// The algorithm (greedy start, Fedorov exchange on smooth surrogates, then
// the exact criterion) is described in excitation.cpp.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "calib/excitation/candidates.hpp"
#include "calib/excitation/fisher.hpp"
#include "calib/excitation/positioning_design.hpp"
#include "models/parameters.hpp"
#include "models/robot.hpp"

namespace gpm::calib::excitation {

enum class Criterion { kDOptimal, kWorst, kPositioning };

// "d" / "worst" -> Criterion; nullopt otherwise.
std::optional<Criterion> parse_criterion(std::string_view name);
std::string_view criterion_name(Criterion c);

struct DesignOptions {
  int count = 50;                       // number of poses (>= number of free parameters)
  double sigma = 1e-4;                  // encoder noise, rad (scales the bounds only)
  FreeMask free = default_free_mask();  // parameters to calibrate
  Criterion criterion = Criterion::kWorst;
  PositioningPrior positioning;         // kPositioning: the error's prior, readings per pose, disc
  double grid_step_mm = 5.0;            // candidate grid spacing
  Guard guard;                          // candidates stricter than the robot's limits
  // Optional further test every candidate must pass (e.g. the hardware's
  // safety limits); unset: every guarded reachable grid point is a candidate.
  std::function<bool(const Eigen::Vector2d&)> admissible;
  int max_exchanges = 2000;             // per exchange stage
  // Called after each stage (greedy start, then each exchange stage) with
  // the stages done and their number; empty: none.
  std::function<void(int done, int stages)> progress;
};

// Design options from a caller's numbers, each within its documented range
// (models/bounds.hpp) and the criterion by name; errors name the argument as
// the caller spells it: "--grid-step" on the command line (cli), "grid_step"
// in Python.
DesignOptions checked_design_options(double count, double sigma, const FreeMask& free, std::string_view criterion,
                                     double grid_step_mm, double guard_mm, bool cli);

struct Design {
  std::vector<Eigen::Vector2d> poses;  // the chosen poses (mm)
  std::vector<Eigen::Vector2d> start;  // the greedy start
  Bounds bounds;                       // of poses, at the nominal geometry
  Bounds start_bounds;                 // of the greedy start
  int candidates = 0;                  // size of the candidate grid
  int exchanges = 0;                   // swaps made in all exchange stages
  double positioning_bound_um = 0.0;   // kPositioning: the criterion's value (um); 0 otherwise
};

// The stages design_poses reports to DesignOptions::progress for criterion c.
int design_stages(Criterion c);

// The value of a criterion for bounds b (smaller is better: -log det F for D,
// worst_mm for worst and for positioning, whose own value needs more than b).
double criterion_value(Criterion c, const Bounds& b);

// Greedy D-optimal choice of count distinct rows (indices into rows), from
// the ridge delta * I (delta relative to the mean squared row norm).
std::vector<int> greedy_d_optimal(const Eigen::MatrixXd& rows, int count, double delta = 1e-6);

// Fedorov exchange maximising log det of the chosen rows' information;
// returns the number of swaps. chosen must be nonsingular.
int exchange_d_optimal(const Eigen::MatrixXd& rows, std::vector<int>& chosen, int max_swaps);

// Exchange minimising sum_k C_kk^q (q >= 1), or max_k C_kk when q = 0, of the
// chosen rows (already scaled so that C_kk are the scaled variances); returns
// the number of swaps. chosen must be nonsingular.
int exchange_variances(const Eigen::MatrixXd& rows, std::vector<int>& chosen, int q, int max_swaps);

// Optimal poses for the robot at its (nominal) geometry. Throws InputError for
// bad options (count below the number of free parameters or above the
// number of candidates, sigma <= 0) or a free set that no poses identify.
Design design_poses(const Robot& nominal, const DesignOptions& options);

}  // namespace gpm::calib::excitation
