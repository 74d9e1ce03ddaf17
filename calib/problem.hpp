// A calibration problem and its result, shared by the local (Ceres LM) and
// global (GA, PSO, DE) solvers. Millimetres and radians (docs/ARCHITECTURE.md).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "models/parameters.hpp"
#include "models/samples.hpp"

namespace gpm::calib {

// Error functions: J1 (eq. 36-37), J2 (eq. 38-39), J3 (eq. 42-43, decoupled
// l_ac, l_as) and ML, the closure residual divided by the norm of its gradient
// with respect to the three readings (maximum likelihood under encoder noise).
enum class Cost { kJ1, kJ2, kJ3, kML };

// "j1", "j2", "j3", "ml" -> Cost; nullopt for anything else.
std::optional<Cost> parse_cost(std::string_view name);
std::string_view cost_name(Cost c);

// Calibration methods (calib/calibrate.hpp): Ceres Levenberg-Marquardt, the
// population optimisers GA, PSO, DE of calib/global (paper section 4), and DE
// followed by LM.
enum class Method { kLM, kGA, kPSO, kDE, kDELM };

// The names parse_method accepts, for messages.
inline constexpr const char* kMethodNames = "lm, ga, pso, de, de+lm";

// "lm", "ga", "pso", "de", "de+lm" -> Method. Throws InputError with one line
// "<where>: unknown method '<name>' (valid: lm, ga, pso, de, de+lm)" otherwise.
Method parse_method(std::string_view name, std::string_view where = "--method");
std::string_view method_name(Method m);

// What to estimate from which readings.
struct Problem {
  std::vector<Eigen::Vector3d> theta_m;  // encoder readings per sample (rad)
  Geometry start;                        // initial values; fixed parameters at their known values
  FreeMask free;                         // parameters to estimate
  // The samples' true end-effector positions (mm), one per reading, where
  // known (simulation, a tracker): Result::kmrmse_mm (eq. 40); empty: unknown.
  std::vector<Eigen::Vector2d> true_xy{};
  // Each sample's residual weight, one per reading (1 / its 1-sigma in units
  // of the reading noise, e.g. calib/sample_weights.hpp); empty: all 1.
  std::vector<double> weight{};
};

// Search box of the global solvers (paper Table 5 by default).
struct Box {
  std::array<double, kNumParams> lower{};
  std::array<double, kNumParams> upper{};
};

// One Levenberg-Marquardt iteration (Ceres' IterationSummary): iteration 0
// is the start; step_norm is |dx| in the solver's parameters (calib/parameterization.hpp).
struct LmIteration {
  int iteration = 0;
  double cost = 0.0;       // J after this step (rejected: J at the point it rejected)
  double step_norm = 0.0;  // the step tried (0 at iteration 0)
  bool accepted = true;    // false: the step raised J and was rejected
};

// Outcome of any solver; written as the result YAML (docs/FORMATS.md).
struct Result {
  Geometry geometry;                        // all 15 (estimated and fixed)
  FreeMask free;
  std::array<double, kNumParams> sigma{};   // 1-sigma of estimated parameters (NaN if unknown)
  std::string method;                       // "lm", "de", ...
  Cost cost = Cost::kJ3;
  double final_cost = 0.0;                  // value of the chosen error function J
  long iterations = 0;
  long evaluations = 0;
  int rank = 0;
  double condition_number = 0.0;
  std::optional<double> kmrmse_mm;          // eq. 40, when samples carry x,y
  double seconds = 0.0;
  bool rank_deficient = false;              // solved with --allow-rank-deficient
  bool converged = true;
  std::vector<std::string> notes;           // warnings and diagnoses, one sentence each
  std::vector<std::pair<long, double>> history;  // (evaluations, best J) for convergence plots
  std::vector<LmIteration> lm_iterations;        // every iteration of the last LM solve (empty: none)
  // Covariance of all 15 parameters (zero rows/columns for fixed ones), when
  // the solver computed one (calib/lm.hpp); sigma holds its diagonal's roots.
  std::optional<Eigen::Matrix<double, kNumParams, kNumParams>> covariance;
  // The part of covariance that an error carried unestimated adds (the error
  // once per joint revolution under its prior: calib/motion_correction.hpp),
  // when one is carried; covariance includes it.
  std::optional<Eigen::Matrix<double, kNumParams, kNumParams>> carried_covariance;
};

}  // namespace gpm::calib
