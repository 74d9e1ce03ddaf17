#include "calib/global/population_cost.hpp"

#include <algorithm>

#include <thread>

#include "models/errors.hpp"

namespace gpm::calib::global {

PopulationCost::PopulationCost(const Problem& problem, Cost cost, const Box& box, int threads)
    : space_(problem, cost, box), table_(make_sample_table(problem.theta_m)), threads_(threads) {
  if (problem.theta_m.empty()) throw InputError("global solvers: no samples");
  if (threads < 0) throw InputError("global solvers: the thread count must be >= 0");
  const int nt = threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (nt > 1) pool_ = std::make_shared<BlockPool>(nt - 1);
}

void PopulationCost::evaluate(const double* x, long stride, long count, double* f) const {
  constexpr int B = kKernelBlock;
  const long blocks = (count + B - 1) / B;
  const auto run_block = [&](long b) {
    double kv[kNumKernelVars * B];
    double J[B];
    const long c0 = b * B;
    const long m = std::min<long>(B, count - c0);
    space_.to_kernel(x + c0, stride, m, kv);
    closure_cost_block(space_.cost(), table_, kv, J);
    std::copy_n(J, m, f + c0);
  };
  if (pool_ && blocks > 1) {
    pool_->run(blocks, run_block);
    return;
  }
  for (long b = 0; b < blocks; ++b) run_block(b);
}

double PopulationCost::evaluate_one(const std::vector<double>& d) const {
  if (static_cast<int>(d.size()) != space_.dim())
    throw InputError("global solvers: decision vector of the wrong size");
  double kv[kNumKernelVars];
  space_.to_kernel_one(d.data(), kv);
  return closure_cost_single(space_.cost(), table_, kv);
}

BatchObjective PopulationCost::objective() const {
  BatchObjective obj;
  obj.lower = space_.lower();
  obj.upper = space_.upper();
  obj.evaluate = [this](const double* x, long stride, long count, double* f) {
    evaluate(x, stride, count, f);
  };
  return obj;
}

}  // namespace gpm::calib::global
