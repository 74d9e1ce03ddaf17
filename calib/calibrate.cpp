#include "calib/calibrate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include <ceres/ceres.h>

#include <fmt/format.h>

#include "calib/global/decision_space.hpp"
#include "calib/global/global.hpp"
#include "calib/kmrmse.hpp"
#include "calib/lm.hpp"
#include "calib/parameterization.hpp"
#include "calib/residuals.hpp"
#include "models/errors.hpp"

namespace gpm::calib {

namespace {

// Residuals of one sample at geometry g under cost c.
Eigen::VectorXd sample_residuals(Cost c, const Eigen::Vector3d& theta_m, const Geometry& g) {
  const ParamVector x = to_solver(g, c);
  const std::unique_ptr<ceres::CostFunction> f(make_residual(c, theta_m));
  Eigen::VectorXd r(residual_rows(c));
  const double* params[] = {x.data()};
  if (!f->Evaluate(params, r.data(), nullptr)) r.setConstant(std::numeric_limits<double>::quiet_NaN());
  return r;
}

// LM with the robust loss of o.loss (calib/calibrate.hpp: its default scale).
Result robust_lm(const Problem& problem, LmOptions lm, const RobustLoss& loss) {
  lm.loss = loss;
  if (!loss.active() || loss.scale > 0.0) return calibrate_lm(problem, lm);
  const double tuning = default_tuning(loss.kind);
  Problem p = problem;
  double sigma = lm.encoder_sigma.value_or(0.0);
  if (!(sigma > 0.0)) {
    // Noise from the residuals of a plain fit, robustly (median absolute residual).
    LmOptions plain = lm;
    plain.loss = {};
    plain.compute_covariance = false;
    const Result first = calibrate_lm(problem, plain);
    p.start = first.geometry;
    std::vector<double> a;
    for (const Eigen::Vector3d& t : problem.theta_m) {
      const Eigen::VectorXd r = sample_residuals(lm.cost, t, first.geometry);
      a.insert(a.end(), r.begin(), r.end());
    }
    sigma = robust_sigma(std::move(a));
    if (!(sigma > 0.0)) return first;  // exact data: nothing to be robust against
  }
  lm.loss.scale = tuning * sigma;
  return calibrate_lm(p, lm);
}

}  // namespace

Result calibrate(const Problem& problem, const MethodOptions& o) {
  LmOptions lm;
  lm.cost = o.cost;
  lm.encoder_sigma = o.encoder_sigma;
  lm.allow_rank_deficient = o.allow_rank_deficient;
  lm.max_iterations = o.lm_max_iterations;
  if (o.method == Method::kLM) return robust_lm(problem, lm, o.loss);
  if (o.loss.active() && o.method != Method::kDELM)
    throw InputError(fmt::format("--loss {} works with lm or de+lm (the LM stage); {} is not robustified",
                                 loss_name(o.loss), method_name(o.method)));

  const bool ml = o.cost == Cost::kML;
  if (ml && o.method != Method::kDELM) {
    throw InputError(fmt::format("--cost ml works with lm or de+lm only; {} minimises j1, j2 or j3",
                                 method_name(o.method)));
  }
  global::GlobalOptions go;
  go.budget = o.budget;
  go.seed = o.seed;
  go.allow_rank_deficient = o.allow_rank_deficient;
  go.lm_max_iterations = o.lm_max_iterations;
  const Box box = global::default_box(problem.start, problem.free);
  // ML is a least-squares residual, not a population cost: DE searches J3
  // (same minimiser, docs/EQUATIONS.md), then LM refines on ML.
  Result g = global::solve_global(problem, ml ? Cost::kJ3 : o.cost, ml ? Method::kDE : o.method, box, go,
                                 o.progress);
  if (problem.true_xy.size() == problem.theta_m.size())
    g.kmrmse_mm = kmrmse(g.geometry, problem.theta_m, problem.true_xy);
  if (!ml) return g;
  Problem refine = problem;
  refine.start = g.geometry;
  Result r = robust_lm(refine, lm, o.loss);
  r.method = "de+lm";
  r.evaluations += g.evaluations;
  r.seconds += g.seconds;
  r.notes.insert(r.notes.begin(), fmt::format("DE stage on j3: {} evaluations, best J3 = {:.4g}", g.evaluations,
                                              g.final_cost));
  return r;
}

}  // namespace gpm::calib
