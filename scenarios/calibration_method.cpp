#include "scenarios/calibration_method.hpp"

#include <fmt/format.h>

#include "calib/global/decision_space.hpp"
#include "calib/global/global.hpp"
#include "calib/kmrmse.hpp"
#include "calib/lm.hpp"
#include "models/errors.hpp"

namespace gpm::scenario {

calib::Result calibrate_with_method(const calib::Problem& problem, const MethodOptions& o) {
  calib::LmOptions lm;
  lm.cost = o.cost;
  lm.encoder_sigma = o.encoder_sigma;
  lm.allow_rank_deficient = o.allow_rank_deficient;
  lm.true_xy = o.true_xy;
  lm.max_iterations = o.lm_max_iterations;
  if (o.method == "lm") return calib::calibrate_lm(problem, lm);

  const auto method = calib::global::parse_method(o.method);
  if (!method) {
    throw InputError(fmt::format("--method: unknown method '{}' (valid: {})", o.method, kMethodNames));
  }
  const bool ml = o.cost == calib::Cost::kML;
  if (ml && *method != calib::global::Method::kDeLm) {
    throw InputError(fmt::format("--cost ml works with lm or de+lm only; {} minimises j1, j2 or j3", o.method));
  }
  calib::global::GlobalOptions go;
  go.budget = o.budget;
  go.seed = o.seed;
  go.allow_rank_deficient = o.allow_rank_deficient;
  go.lm_max_iterations = o.lm_max_iterations;
  const calib::Box box = calib::global::default_box(problem.start, problem.free);
  // ML is a least-squares residual, not a population cost: DE searches J3
  // (same minimiser, ERRATA), then LM refines on ML.
  calib::Result g = calib::global::solve_global(
      problem, ml ? calib::Cost::kJ3 : o.cost, ml ? calib::global::Method::kDe : *method, box, go);
  if (o.true_xy) g.kmrmse_mm = calib::kmrmse(g.geometry, problem.theta_m, *o.true_xy);
  if (!ml) return g;
  calib::Problem refine = problem;
  refine.start = g.geometry;
  calib::Result r = calib::calibrate_lm(refine, lm);
  r.method = "de+lm";
  r.evaluations += g.evaluations;
  r.seconds += g.seconds;
  r.notes.insert(r.notes.begin(), fmt::format("DE stage on j3: {} evaluations, best J3 = {:.4g}", g.evaluations,
                                              g.final_cost));
  return r;
}

}  // namespace gpm::scenario
