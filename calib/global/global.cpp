#include "calib/global/global.hpp"

#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "calib/global/population_cost.hpp"
#include "calib/identifiability.hpp"
#include "calib/lm.hpp"
#include "models/errors.hpp"

namespace gpm::calib::global {

Result solve_global(const Problem& problem, Cost cost, Method method, const Box& box,
                    const GlobalOptions& opt, const ProgressFn& progress) {
  if (method == Method::kLM) throw InputError("global solvers: lm is not a global method (use calib::calibrate)");
  if (opt.budget < 1) throw InputError("global solvers: the budget must be at least 1 evaluation");
  const auto t0 = std::chrono::steady_clock::now();
  const PopulationCost pc(problem, cost, box, opt.threads);
  const BatchObjective obj = pc.objective();
  const StopRule stop{opt.budget, opt.target};
  RunRecord run;
  switch (method) {
    case Method::kLM: break;
    case Method::kGA: run = minimise_ga(obj, opt.ga, stop, opt.seed, progress); break;
    case Method::kPSO: run = minimise_pso(obj, opt.pso, stop, opt.seed, progress); break;
    case Method::kDE:
    case Method::kDELM: run = minimise_de(obj, opt.de, stop, opt.seed, progress); break;
  }

  Result r;
  r.free = problem.free;
  r.geometry = run.best_x.empty() ? problem.start : pc.space().to_geometry(run.best_x);
  r.sigma.fill(std::nan(""));
  r.method = std::string(method_name(method));
  r.cost = cost;
  r.final_cost = run.best_f;
  r.iterations = run.generations;
  r.evaluations = run.evaluations;
  r.history = std::move(run.history);
  r.converged = std::isfinite(run.best_f);

  if (method == Method::kDELM && !run.best_x.empty()) {
    Problem refine = problem;
    refine.start = r.geometry;
    LmOptions lm;
    lm.cost = cost;
    lm.max_iterations = opt.lm_max_iterations;
    lm.allow_rank_deficient = opt.allow_rank_deficient;
    const Result local = calibrate_lm(refine, lm);
    r.geometry = local.geometry;
    r.sigma = local.sigma;
    r.evaluations += local.evaluations;
    r.iterations += local.iterations;
    r.converged = local.converged;
    for (const auto& note : local.notes) r.notes.push_back("lm: " + note);
    r.final_cost = pc.evaluate_one(pc.space().from_geometry(r.geometry));
    r.history.emplace_back(r.evaluations, std::min(r.final_cost, run.best_f));
  }

  const Identifiability id = analyse_identifiability(problem.theta_m, r.geometry, problem.free);
  r.rank = id.rank;
  r.condition_number = id.condition_number;
  r.rank_deficient = id.rank < id.free_count;
  r.notes.insert(r.notes.begin(), id.diagnosis);
  if (r.rank_deficient)
    r.notes.push_back(fmt::format(
        "{} reached J = {:.4g}, but with rank {} of {} a different seed lands on a different, "
        "equally perfect parameter set: the values are not an identification",
        r.method, r.final_cost, id.rank, id.free_count));
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

Result solve_global(const Problem& problem, Cost cost, Method method, const Box& box, long budget,
                    uint64_t seed, const ProgressFn& progress) {
  GlobalOptions opt;
  opt.budget = budget;
  opt.seed = seed;
  return solve_global(problem, cost, method, box, opt, progress);
}

}  // namespace gpm::calib::global
