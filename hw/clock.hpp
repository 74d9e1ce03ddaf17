// The time source of the hardware layer, injected where time is measured or
// waited for (CycleClock, SafetySupervisor comms timing, DriveBackend's
// enable wait, ModbusTransport's response timeout, DriveEmulator), so tests
// drive a ManualClock instead of sleeping on the wall clock. A client and the
// drive emulator given one ManualClock run stepped: the clock moves only when
// the client waits for its next cycle (sleep_until jumps) or the emulator
// delays or stalls a reply, and nothing depends on the wall time.
#pragma once

#include <atomic>

namespace gpm::hw {

class Clock {
 public:
  virtual ~Clock() = default;
  // Seconds on a monotonic scale (the origin is arbitrary).
  virtual double now() const = 0;
  // Returns once now() >= t (at once if it already is).
  virtual void sleep_until(double t) = 0;
};

// The wall clock (std::chrono::steady_clock); shared, stateless.
Clock& steady_clock();

// A clock that moves only when told: advance() or sleep_until() (which jumps
// to t). With follow_wall it is the wall clock plus its offset (sleep_until
// waits in real time), for real-time tests that need to skip ahead (e.g. past
// a comms watchdog).
// Thread-safe.
class ManualClock final : public Clock {
 public:
  explicit ManualClock(bool follow_wall = false) : follow_wall_(follow_wall) {}
  double now() const override;
  void sleep_until(double t) override;
  // Moves the clock forward by dt seconds.
  void advance(double dt);
  // Number of sleep_until calls that had to wait (t > now()).
  long waits() const { return waits_.load(); }

 private:
  bool follow_wall_;
  std::atomic<double> offset_{0.0};
  std::atomic<long> waits_{0};
};

}  // namespace gpm::hw
