// Fixed-rate cycle timing for the read/write loop: the time of the current
// cycle and a wait for the next. Real drives pace on a clock (the wall clock
// unless another is injected: tests use a ManualClock); a simulated backend
// advances time by one period per cycle without waiting.
#pragma once

#include "hw/clock.hpp"

namespace gpm::hw {

class CycleClock {
 public:
  // A clock ticking every period_s; simulated: no waiting. clock paces the
  // cycles (the wall clock by default).
  CycleClock(double period_s, bool simulated, Clock& clock = steady_clock());
  // Time of the current cycle (s since construction, or since the simulated start).
  double now() const { return t_; }
  // Advances to the next cycle (waits until it on the clock unless simulated).
  void wait_next();
  // Cycles that started late by more than one period (paced clock only).
  long overruns() const { return overruns_; }

 private:
  double period_;
  bool simulated_;
  Clock& clock_;
  double t_ = 0.0;
  long overruns_ = 0;
  double start_;
};

}  // namespace gpm::hw
