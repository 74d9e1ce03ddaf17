#include "hw/cycle_clock.hpp"

#include <thread>

namespace gpm::hw {

CycleClock::CycleClock(double period_s, bool simulated)
    : period_(period_s), simulated_(simulated), start_(std::chrono::steady_clock::now()) {}

void CycleClock::wait_next() {
  t_ += period_;
  if (simulated_) return;
  const auto due = start_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                std::chrono::duration<double>(t_));
  const auto now = std::chrono::steady_clock::now();
  if (now > due + std::chrono::duration<double>(period_)) {
    ++overruns_;
    // Late: restart the schedule from now rather than bursting to catch up.
    t_ = std::chrono::duration<double>(now - start_).count();
    return;
  }
  std::this_thread::sleep_until(due);
}

}  // namespace gpm::hw
