// J1, J2 or J3 of a calibration problem over whole populations of decision
// vectors, spread over threads. Each candidate's value is computed by one
// thread in a fixed order, so results do not depend on the thread count.
#pragma once

#include <memory>

#include "calib/global/block_pool.hpp"
#include "calib/global/closure_kernel.hpp"
#include "calib/global/decision_space.hpp"
#include "calib/global/objective.hpp"

namespace gpm::calib::global {

class PopulationCost {
 public:
  // threads: 0 = all hardware threads, 1 = serial (threads - 1 helpers are
  // started here and share each population with the calling thread).
  PopulationCost(const Problem& problem, Cost cost, const Box& box, int threads = 0);

  const DecisionSpace& space() const { return space_; }
  const SampleTable& table() const { return table_; }

  // f[c] = J of candidate c (x[k * stride + c], c < count).
  void evaluate(const double* x, long stride, long count, double* f) const;

  // J of one decision vector.
  double evaluate_one(const std::vector<double>& d) const;

  // The objective for GA, PSO, DE (refers to *this: keep it alive).
  BatchObjective objective() const;

 private:
  DecisionSpace space_;
  SampleTable table_;
  int threads_;
  std::shared_ptr<BlockPool> pool_;  // null when serial
};

}  // namespace gpm::calib::global
