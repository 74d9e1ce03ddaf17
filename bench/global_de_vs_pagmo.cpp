// Our DE against pagmo2's DE (rand/1/bin, N = 150, F = 0.5, CR = 0.8) on J3 of
// the 11 identifiable parameters (Table 5, 50 samples), same budget of 1.5e6
// evaluations: wall time and final J, plus the evaluations our DE needs to
// reach J3 < 1e-18.
#include <vector>

#include <benchmark/benchmark.h>

#ifdef GPM_HAVE_PAGMO
#include <pagmo/algorithm.hpp>
#include <pagmo/algorithms/de.hpp>
#include <pagmo/population.hpp>
#include <pagmo/problem.hpp>
#endif

#include "calib/global/de.hpp"
#include "calib/global/population_cost.hpp"
#include "calib/paper_values.hpp"
#include "calib/synthetic.hpp"

namespace {

using namespace gpm;
using namespace gpm::calib;
using namespace gpm::calib::global;

constexpr long kBudget = 1'500'000;
constexpr int kPopulation = 150;

Problem bench_problem() {
  Robot actual;
  actual.geometry = table5_actual();
  return table5_problem(workspace_samples(actual, 50, 42), default_free_mask());
}

void BM_OurDe(benchmark::State& state) {
  const Problem p = bench_problem();
  const PopulationCost pc(p, Cost::kJ3, default_box(Geometry::gpm2002_nominal(), p.free),
                          static_cast<int>(state.range(0)));
  const BatchObjective obj = pc.objective();
  RunRecord rec;
  uint64_t seed = 1;
  for (auto _ : state) rec = minimise_de(obj, DeSettings{}, StopRule{kBudget}, seed++);
  state.counters["final_J3"] = rec.best_f;
  state.counters["evaluations"] = static_cast<double>(rec.evaluations);
  long to_floor = -1;
  for (const auto& [e, f] : rec.history)
    if (f < 1e-18) { to_floor = e; break; }
  state.counters["evals_to_1e-18"] = static_cast<double>(to_floor);
}
BENCHMARK(BM_OurDe)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime()->Iterations(3);

void BM_OurDeToTarget(benchmark::State& state) {
  const Problem p = bench_problem();
  const PopulationCost pc(p, Cost::kJ3, default_box(Geometry::gpm2002_nominal(), p.free), 2);
  const BatchObjective obj = pc.objective();
  RunRecord rec;
  uint64_t seed = 1;
  double worst_evals = 0;
  for (auto _ : state) {
    rec = minimise_de(obj, DeSettings{}, StopRule{kBudget, 1e-18}, seed++);
    worst_evals = std::max(worst_evals, static_cast<double>(rec.evaluations));
  }
  state.counters["final_J3"] = rec.best_f;
  state.counters["max_evals_to_1e-18"] = worst_evals;
}
BENCHMARK(BM_OurDeToTarget)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(5);

#ifdef GPM_HAVE_PAGMO
// The same J3 as a pagmo user-defined problem (one candidate per call).
struct J3Problem {
  const PopulationCost* pc = nullptr;
  pagmo::vector_double fitness(const pagmo::vector_double& x) const { return {pc->evaluate_one(x)}; }
  std::pair<pagmo::vector_double, pagmo::vector_double> get_bounds() const {
    return {pc->space().lower(), pc->space().upper()};
  }
};

void BM_PagmoDe(benchmark::State& state) {
  const Problem p = bench_problem();
  const PopulationCost pc(p, Cost::kJ3, default_box(Geometry::gpm2002_nominal(), p.free), 1);
  const unsigned generations = static_cast<unsigned>((kBudget - kPopulation) / kPopulation);
  double final_f = 0;
  unsigned long long fevals = 0;
  unsigned seed = 1;
  for (auto _ : state) {
    pagmo::problem prob{J3Problem{&pc}};
    pagmo::population pop{prob, kPopulation, seed};
    pagmo::algorithm algo{pagmo::de(generations, 0.5, 0.8, 7u, 0.0, 0.0, seed)};
    ++seed;
    pop = algo.evolve(pop);
    final_f = pop.champion_f()[0];
    fevals = pop.get_problem().get_fevals();
  }
  state.counters["final_J3"] = final_f;
  state.counters["evaluations"] = static_cast<double>(fevals);
}
BENCHMARK(BM_PagmoDe)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
#endif

}  // namespace
