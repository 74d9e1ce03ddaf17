#include "hw/procedures/cycle_clock.hpp"

namespace gpm::hw {

CycleClock::CycleClock(double period_s, bool simulated, Clock& clock)
    : period_(period_s), simulated_(simulated), clock_(clock), start_(clock.now()) {}

void CycleClock::wait_next() {
  t_ += period_;
  if (simulated_) return;
  const double due = start_ + t_;
  const double now = clock_.now();
  if (now > due + period_) {
    ++overruns_;
    // Late: restart the schedule from now rather than bursting to catch up.
    t_ = now - start_;
    return;
  }
  clock_.sleep_until(due);
}

}  // namespace gpm::hw
