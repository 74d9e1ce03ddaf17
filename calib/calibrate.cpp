#include "calib/calibrate.hpp"

#include <fmt/format.h>

#include "calib/global/decision_space.hpp"
#include "calib/global/global.hpp"
#include "calib/kmrmse.hpp"
#include "calib/lm.hpp"
#include "models/errors.hpp"

namespace gpm::calib {

Result calibrate(const Problem& problem, const MethodOptions& o) {
  LmOptions lm;
  lm.cost = o.cost;
  lm.encoder_sigma = o.encoder_sigma;
  lm.allow_rank_deficient = o.allow_rank_deficient;
  lm.true_xy = o.true_xy;
  lm.max_iterations = o.lm_max_iterations;
  if (o.method == Method::kLM) return calibrate_lm(problem, lm);

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
  Result g = global::solve_global(problem, ml ? Cost::kJ3 : o.cost, ml ? Method::kDE : o.method, box, go);
  if (o.true_xy) g.kmrmse_mm = kmrmse(g.geometry, problem.theta_m, *o.true_xy);
  if (!ml) return g;
  Problem refine = problem;
  refine.start = g.geometry;
  Result r = calibrate_lm(refine, lm);
  r.method = "de+lm";
  r.evaluations += g.evaluations;
  r.seconds += g.seconds;
  r.notes.insert(r.notes.begin(), fmt::format("DE stage on j3: {} evaluations, best J3 = {:.4g}", g.evaluations,
                                              g.final_cost));
  return r;
}

}  // namespace gpm::calib
