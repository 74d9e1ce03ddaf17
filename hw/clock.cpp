#include "hw/clock.hpp"

#include <chrono>
#include <thread>

namespace gpm::hw {
namespace {

double wall_now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

class SteadyClock final : public Clock {
 public:
  double now() const override { return wall_now(); }
  void sleep_until(double t) override {
    const double dt = t - wall_now();
    if (dt > 0) std::this_thread::sleep_for(std::chrono::duration<double>(dt));
  }
};

}  // namespace

Clock& steady_clock() {
  static SteadyClock clock;
  return clock;
}

double ManualClock::now() const { return (follow_wall_ ? wall_now() : 0.0) + offset_.load(); }

void ManualClock::sleep_until(double t) {
  const double now_t = now();
  if (t <= now_t) return;
  ++waits_;
  if (follow_wall_) {  // real time passes: wait for it
    std::this_thread::sleep_for(std::chrono::duration<double>(t - now_t));
    return;
  }
  advance(t - now_t);
}

void ManualClock::advance(double dt) {
  double o = offset_.load();
  while (!offset_.compare_exchange_weak(o, o + dt)) {
  }
}

}  // namespace gpm::hw
