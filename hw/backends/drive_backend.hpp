// Backend over servo drives reached through any RegisterTransport, with the
// register map naming where each value lives. With a ModbusTransport it is
// the `modbus` backend; the drive logic (enable, command, status, faults)
// does not depend on the protocol. Time is the injected clock (the wall clock). With a latch in
// the map (register_map.hpp) each read first triggers it, so the three
// readings are of one instant although the drives are read one by one.
// Stepped timing (the drive emulator's --stepped, a simulator in lock step):
// the drives advance one period per latch trigger, so the procedure's time
// is the count of its cycles, and every read checks the drives' latch time.
#pragma once

#include <memory>

#include "hw/backends/register_map.hpp"
#include "hw/backends/register_transport.hpp"
#include "hw/clock.hpp"
#include "hw/robot_hardware.hpp"

namespace gpm::hw {

// How the drives' time advances: on their own clock (real drives; the client
// paces its cycles on the wall clock) or one period per client cycle.
enum class DriveTiming { kRealTime, kStepped };

class DriveBackend final : public RobotHardware {
 public:
  // Drives described by map, reached through transport (owned), cycled every
  // period_s; clock times the wait for the power stages (tests inject one).
  // Stepped timing needs a latch with its time register (else InputError).
  DriveBackend(const RegisterMap& map, std::unique_ptr<RegisterTransport> transport,
               double period_s, Clock& clock = steady_clock(), DriveTiming timing = DriveTiming::kRealTime);
  ~DriveBackend() override;

  double period_s() const override { return period_s_; }
  // Stepped: time advances with the cycles only (the drives wait for the client).
  bool simulated_time() const override { return timing_ == DriveTiming::kStepped; }
  std::string describe() const override { return transport_->describe(); }

 protected:
  void on_configure(HardwareState& initial) override;
  void on_activate(const HardwareState& current) override;
  void on_deactivate() override;
  void on_shutdown() noexcept override;
  void on_error() noexcept override;
  void on_read(double time_s, HardwareState& state) override;
  void on_write(const HardwareCommand& command, double time_s) override;

 private:
  void read_axes(double time_s, HardwareState& s);
  // Stepped: throws HardwareError unless the latch's time (registers r from
  // address lo) is one period after the one before.
  void check_step(const std::vector<std::uint16_t>& r, int lo);
  void set_enable(int axis, bool on);
  void disable_all() noexcept;

  RegisterMap map_;
  std::unique_ptr<RegisterTransport> transport_;
  double period_s_;
  Clock& clock_;
  std::array<std::uint16_t, 3> control_{};   // last control word written per axis
  std::array<bool, 3> enable_{};             // enable bit requested per axis
  std::uint16_t latch_id_ = 0;              // id of the last latch triggered (map with a latch)
  DriveTiming timing_;
  long long latch_us_ = -1;                 // stepped: the drives' time at the last latch (us; -1: none yet)
  bool have_previous_ = false;
  HardwareState previous_;
};

}  // namespace gpm::hw
