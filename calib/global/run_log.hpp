// Bookkeeping shared by GA, PSO and DE: the evaluation count against the
// budget, the best value so far, a log-spaced convergence history (paper
// Figs. 3-5) and progress reports.
#pragma once

#include <algorithm>
#include <cmath>

#include "calib/global/objective.hpp"

namespace gpm::calib::global {

class RunLog {
 public:
  RunLog(const StopRule& stop, const ProgressFn& progress, RunRecord& record)
      : stop_(stop), progress_(progress), rec_(record) {}

  // Evaluations still allowed by the budget.
  long remaining() const { return std::max(0L, stop_.budget - rec_.evaluations); }

  // True when the budget is spent or the target reached.
  bool done() const { return remaining() == 0 || rec_.best_f <= stop_.target; }

  // Counts n evaluations just made.
  void count(long n) { rec_.evaluations += n; }

  // Offers a candidate; keeps it when strictly better than the best so far.
  // Returns true if it became the best.
  template <class GetX>
  bool offer(double f, GetX&& get_x) {
    if (!(f < rec_.best_f)) return false;
    rec_.best_f = f;
    get_x(rec_.best_x);
    return true;
  }

  // Call once per generation: records history at log-spaced evaluation counts
  // (40 per decade) and reports progress every 1% of the budget.
  void end_generation() {
    ++rec_.generations;
    const long e = rec_.evaluations;
    if (e >= next_history_ || done()) {
      if (rec_.history.empty() || rec_.history.back().first != e) rec_.history.emplace_back(e, rec_.best_f);
      while (static_cast<double>(next_history_) <= static_cast<double>(e))
        next_history_ = static_cast<long>(std::ceil(static_cast<double>(next_history_) * kStep)) + 1;
    }
    if (progress_ && (e >= next_progress_ || done())) {
      progress_(e, stop_.budget, rec_.best_f);
      next_progress_ = e + std::max(1L, stop_.budget / 100);
    }
  }

 private:
  static constexpr double kStep = 1.0592537251772889;  // 10^(1/40)
  const StopRule& stop_;
  const ProgressFn& progress_;
  RunRecord& rec_;
  long next_history_ = 1;
  long next_progress_ = 0;
};

}  // namespace gpm::calib::global
