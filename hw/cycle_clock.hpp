// Fixed-rate cycle timing for the read/write loop: the time of the current
// cycle and a wait for the next. Real drives pace on the wall clock; a
// simulated backend advances time by one period per cycle without sleeping.
#pragma once

#include <chrono>

namespace gpm::hw {

class CycleClock {
 public:
  // A clock ticking every period_s; simulated: no sleeping.
  CycleClock(double period_s, bool simulated);
  // Time of the current cycle (s since construction, or since the simulated start).
  double now() const { return t_; }
  // Advances to the next cycle (sleeps until it on the wall clock unless simulated).
  void wait_next();
  // Cycles that started late by more than one period (wall clock only).
  long overruns() const { return overruns_; }

 private:
  double period_;
  bool simulated_;
  double t_ = 0.0;
  long overruns_ = 0;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace gpm::hw
