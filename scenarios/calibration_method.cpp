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
  if (o.method == "lm") return calib::calibrate_lm(problem, lm);

  const bool refine = o.method == "de+lm";
  const auto method = calib::global::parse_method(refine ? "de" : o.method);
  if (!method) {
    throw InputError(fmt::format("--method: unknown method '{}' (valid: {})", o.method, kMethodNames));
  }
  calib::Cost global_cost = o.cost;
  if (o.cost == calib::Cost::kML) {
    if (!refine) {
      throw InputError(fmt::format("--cost ml works with lm or de+lm only; {} minimises j1, j2 or j3",
                                   o.method));
    }
    global_cost = calib::Cost::kJ3;
  }
  const calib::Box box = calib::global::default_box(problem.start, problem.free);
  calib::Result g = calib::global::solve_global(problem, global_cost, *method, box, o.budget, o.seed);
  if (o.true_xy) g.kmrmse_mm = calib::kmrmse(g.geometry, problem.theta_m, *o.true_xy);
  if (!refine) return g;
  calib::Problem second = problem;
  second.start = g.geometry;
  calib::Result r = calib::calibrate_lm(second, lm);
  r.method = "de+lm";
  r.evaluations += g.evaluations;
  r.seconds += g.seconds;
  r.notes.insert(r.notes.begin(), fmt::format("DE stage: {} evaluations of {}, best J = {:.4g}",
                                              g.evaluations, calib::cost_name(global_cost), g.final_cost));
  std::vector<std::pair<long, double>> history = g.history;
  for (const auto& [e, j] : r.history) history.emplace_back(e + g.evaluations, j);
  r.history = std::move(history);
  return r;
}

}  // namespace gpm::scenario
