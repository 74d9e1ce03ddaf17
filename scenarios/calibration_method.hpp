// One entry point for every calibration method of `gpm calibrate` and
// `gpm run`: Ceres LM (calib/lm.hpp), GA, PSO, DE (calib/global), and DE
// followed by LM.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "calib/problem.hpp"

namespace gpm::scenario {

struct MethodOptions {
  std::string method = "lm";  // lm | ga | pso | de | de+lm
  calib::Cost cost = calib::Cost::kML;
  long budget = 1500000;      // error-function evaluations of the global stage
  int lm_max_iterations = 200;
  std::uint64_t seed = 1;
  std::optional<double> encoder_sigma;
  bool allow_rank_deficient = false;
  const std::vector<Eigen::Vector2d>* true_xy = nullptr;
};

// Valid method names, for messages.
inline constexpr const char* kMethodNames = "lm, ga, pso, de, de+lm";

// Solves problem with the chosen method. Global stages use J1/J2/J3 (ML is
// LM only: for `de+lm` with cost ml, DE runs on J3 and LM refines on ML).
// Throws InputError for an unknown method or a cost the method cannot use.
calib::Result calibrate_with_method(const calib::Problem& problem, const MethodOptions& options);

}  // namespace gpm::scenario
