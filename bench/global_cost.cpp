// Throughput of the batch closure costs: J1, J2, J3 evaluations per second
// for 50 samples, 11 free parameters, 1 and 2 threads. CPU time is the whole
// process's (all threads), so CPU / wall time is the number of cores used;
// bench/global_threads.sh prints the 2-thread / 1-thread ratios.
#include <vector>

#include <benchmark/benchmark.h>

#include "calib/global/population_cost.hpp"
#include "models/rng.hpp"
#include "calib/paper_values.hpp"
#include "calib/synthetic.hpp"

namespace {

using namespace gpm;
using namespace gpm::calib;
using namespace gpm::calib::global;

void BM_PopulationCost(benchmark::State& state, Cost cost) {
  const int threads = static_cast<int>(state.range(0));
  Robot actual;
  actual.geometry = table5_actual();
  const Samples s = workspace_samples(actual, 50, 42);
  const Problem p = table5_problem(s, default_free_mask());
  const PopulationCost pc(p, cost, default_box(Geometry::gpm2002_nominal(), p.free), threads);
  const long count = 1536;  // a multiple of the kernel block
  const int n = pc.space().dim();
  std::vector<double> x(static_cast<size_t>(n * count)), f(static_cast<size_t>(count));
  Rng rng(1);
  for (int k = 0; k < n; ++k)
    for (long c = 0; c < count; ++c) x[k * count + c] = rng.uniform(pc.space().lower()[k], pc.space().upper()[k]);
  for (auto _ : state) {
    pc.evaluate(x.data(), count, count, f.data());
    benchmark::DoNotOptimize(f.data());
  }
  state.SetItemsProcessed(state.iterations() * count);
  state.counters["evals_per_s"] =
      benchmark::Counter(static_cast<double>(count), benchmark::Counter::kIsIterationInvariantRate);
}

BENCHMARK_CAPTURE(BM_PopulationCost, j3, Cost::kJ3)->Arg(1)->Arg(2)->MeasureProcessCPUTime()->UseRealTime();
BENCHMARK_CAPTURE(BM_PopulationCost, j2, Cost::kJ2)->Arg(1)->Arg(2)->MeasureProcessCPUTime()->UseRealTime();
BENCHMARK_CAPTURE(BM_PopulationCost, j1, Cost::kJ1)->Arg(1)->Arg(2)->MeasureProcessCPUTime()->UseRealTime();

}  // namespace
