#include "hw/backends/drive_backend.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "hw/hw_errors.hpp"
#include "models/errors.hpp"
#include "models/kinematics.hpp"

namespace gpm::hw {
namespace {

bool bit_set(std::uint16_t word, int bit) { return (word >> bit) & 1u; }

constexpr double kEnableTimeoutS = 1.0;  // power stages must report enabled within this

}  // namespace

DriveBackend::DriveBackend(const RegisterMap& map, std::unique_ptr<RegisterTransport> transport,
                           double period_s, Clock& clock, DriveTiming timing)
    : map_(map), transport_(std::move(transport)), period_s_(period_s), clock_(clock), timing_(timing) {
  if (timing_ == DriveTiming::kStepped && !(map_.latch && map_.latch->time_address >= 0))
    throw InputError(fmt::format("{}: stepped timing needs the register map's latch with its time register "
                                 "(latch: {{unit_id, register, time}}): each cycle checks that the drives "
                                 "advanced by one period",
                                 transport_->describe()));
}

void DriveBackend::check_step(const std::vector<std::uint16_t>& r, int lo) {
  const int t = map_.latch->time_address;
  const auto us = static_cast<std::uint32_t>(join32(&r[static_cast<size_t>(t - lo)], map_.word_order));
  const long long before = latch_us_;
  latch_us_ = us;
  if (before < 0) return;
  const auto step = static_cast<long long>(static_cast<std::uint32_t>(us - static_cast<std::uint32_t>(before)));
  if (std::abs(static_cast<double>(step) - period_s_ * 1e6) <= 1.0) return;
  throw HardwareError(fmt::format("{}: the drives' latch time advanced by {:.3f} ms in one cycle where stepped "
                                  "timing steps them by one period ({:.3f} ms): they are not stepped by this "
                                  "client at its rate (gpm-drive-emulator needs --stepped --command-period {:g}; "
                                  "drives on their own clock need modbus.timing: real_time)",
                                  describe(), static_cast<double>(step) * 1e-3, period_s_ * 1e3, period_s_));
}

DriveBackend::~DriveBackend() { disable_all(); }

void DriveBackend::read_axes(double time_s, HardwareState& s) {
  s.time_s = time_s;
  // With a latch, every drive copies its position at one instant; the
  // readings below are those copies, checked to be of this latch.
  std::uint16_t id = 0;
  if (map_.latch) {
    id = ++latch_id_;
    if (id == 0) id = ++latch_id_;  // 0 is what a drive holds before its first latch
    transport_->write(map_.latch->unit_id, map_.latch->address, 1, &id);
  }
  // Without a latch each drive is polled in turn: its reading is of the
  // middle of its request, in the cycle's time base.
  const double cycle_start = clock_.now();
  // Stepped: the latch's time is read with the first axis on the latch's unit (or alone).
  bool time_due = timing_ == DriveTiming::kStepped;
  for (int i = 0; i < 3; ++i) {
    const double asked = clock_.now();
    const AxisRegisters& a = map_.axes[i];
    const int position = map_.latch ? a.latched_position : a.actual_position;
    // One request for the span of everything read from this axis.
    std::vector<int> addrs{position, position + 1, a.status_word, a.enabled.address, a.fault.address};
    if (map_.latch) addrs.push_back(a.latch_id);
    const bool time_here = time_due && a.unit_id == map_.latch->unit_id;
    if (time_here) addrs.insert(addrs.end(), {map_.latch->time_address, map_.latch->time_address + 1});
    if (a.actual_velocity >= 0) addrs.insert(addrs.end(), {a.actual_velocity, a.actual_velocity + 1});
    if (a.actual_torque >= 0) addrs.push_back(a.actual_torque);
    if (a.fault_code >= 0) addrs.push_back(a.fault_code);
    const int lo = *std::min_element(addrs.begin(), addrs.end());
    const int hi = *std::max_element(addrs.begin(), addrs.end());
    std::vector<std::uint16_t> r(static_cast<size_t>(hi - lo + 1));
    if (hi - lo + 1 <= 125) {
      transport_->read(a.unit_id, lo, hi - lo + 1, r.data());
    } else {
      for (int addr : addrs) transport_->read(a.unit_id, addr, 1, &r[static_cast<size_t>(addr - lo)]);
    }
    s.read_time_s[i] = map_.latch ? time_s : time_s + 0.5 * (asked + clock_.now()) - cycle_start;
    auto at = [&](int addr) { return r[static_cast<size_t>(addr - lo)]; };
    if (time_here) {
      check_step(r, lo);
      time_due = false;
    }
    if (map_.latch && at(a.latch_id) != id) {
      throw HardwareError(fmt::format("{}: drive {} (unit {}) holds latch {} where latch {} was just "
                                      "triggered: its reading is not of this cycle's instant",
                                      describe(), i + 1, a.unit_id, at(a.latch_id), id));
    }
    s.theta_m[i] = counts_to_theta(a, join32(&r[static_cast<size_t>(position - lo)], map_.word_order));
    DriveStatus& d = s.drive[i];
    d.status_word = at(a.status_word);
    d.enabled = bit_set(at(a.enabled.address), a.enabled.bit);
    d.fault = bit_set(at(a.fault.address), a.fault.bit);
    d.fault_code = a.fault_code >= 0 ? at(a.fault_code) : 0;
    if (a.actual_velocity >= 0) {
      const double cps = join32(&r[static_cast<size_t>(a.actual_velocity - lo)], map_.word_order);
      s.velocity[i] = a.sign * cps / static_cast<double>(a.counts_per_rev) * 2.0 * M_PI;
    } else if (have_previous_ && time_s > previous_.time_s) {
      s.velocity[i] = wrap_pi(s.theta_m[i] - previous_.theta_m[i]) / (time_s - previous_.time_s);
    } else {
      s.velocity[i] = 0.0;
    }
    s.torque_reported = (i == 0 || s.torque_reported) && a.actual_torque >= 0;
    s.torque[i] = a.actual_torque >= 0
                      ? a.sign * static_cast<std::int16_t>(at(a.actual_torque)) * a.torque_unit_nm
                      : 0.0;
  }
  if (time_due) {  // the latch's unit serves no axis
    std::vector<std::uint16_t> r(2);
    transport_->read(map_.latch->unit_id, map_.latch->time_address, 2, r.data());
    check_step(r, map_.latch->time_address);
  }
  previous_ = s;
  have_previous_ = true;
}

void DriveBackend::set_enable(int i, bool on) {
  const AxisRegisters& a = map_.axes[i];
  std::uint16_t word = control_[i];
  const auto mask = static_cast<std::uint16_t>(1u << a.enable.bit);
  word = on ? static_cast<std::uint16_t>(word | mask) : static_cast<std::uint16_t>(word & ~mask);
  if (a.enable.address != a.control_word) {
    // Enable lives in its own register: read-modify-write it.
    std::uint16_t r = 0;
    transport_->read(a.unit_id, a.enable.address, 1, &r);
    r = on ? static_cast<std::uint16_t>(r | mask) : static_cast<std::uint16_t>(r & ~mask);
    transport_->write(a.unit_id, a.enable.address, 1, &r);
  } else {
    transport_->write(a.unit_id, a.control_word, 1, &word);
    control_[i] = word;
  }
  enable_[i] = on;
}

void DriveBackend::disable_all() noexcept {
  for (int i = 0; i < 3; ++i) {
    try {
      set_enable(i, false);
    } catch (...) {
      // Best effort: the drive's own comms watchdog disables it when we are gone.
    }
  }
}

void DriveBackend::on_configure(HardwareState& initial) {
  transport_->connect();
  for (int i = 0; i < 3; ++i) {
    const AxisRegisters& a = map_.axes[i];
    transport_->read(a.unit_id, a.control_word, 1, &control_[i]);
    set_enable(i, false);
  }
  have_previous_ = false;
  latch_us_ = -1;
  read_axes(0.0, initial);
  // Stepped: a second cycle checks the drives' step before anything is enabled.
  if (timing_ == DriveTiming::kStepped) read_axes(0.0, initial);
  for (int i = 0; i < 3; ++i) {
    if (initial.drive[i].fault) {
      throw HardwareError(fmt::format("{}: drive {} (unit {}) is faulted (fault code 0x{:04x}); "
                                      "clear the fault at the drive first",
                                      describe(), i + 1, map_.axes[i].unit_id,
                                      initial.drive[i].fault_code));
    }
  }
}

void DriveBackend::on_activate(const HardwareState& current) {
  for (int i = 0; i < 3; ++i) {
    const AxisRegisters& a = map_.axes[i];
    const auto regs = split32(theta_to_counts(a, current.theta_m[i]), map_.word_order);
    transport_->write(a.unit_id, a.position_command, 2, regs.data());
    set_enable(i, true);
  }
  // Wait (at most 1 s on the clock; stepped: 1 s of the drives' cycles, each
  // read one) until every power stage reports enabled.
  const bool stepped = timing_ == DriveTiming::kStepped;
  const double deadline = clock_.now() + kEnableTimeoutS;
  HardwareState s = current;
  for (long reads = 1;; ++reads) {
    read_axes(current.time_s, s);
    bool all = true;
    for (int i = 0; i < 3; ++i) {
      if (s.drive[i].fault) {
        throw HardwareError(fmt::format("{}: drive {} faulted while enabling (fault code 0x{:04x})",
                                        describe(), i + 1, s.drive[i].fault_code));
      }
      all = all && s.drive[i].enabled;
    }
    if (all) break;
    if (stepped ? static_cast<double>(reads) * period_s_ > kEnableTimeoutS : clock_.now() > deadline) {
      throw HardwareError(fmt::format("{}: drives did not report enabled within {} s", describe(), kEnableTimeoutS));
    }
    if (!stepped) clock_.sleep_until(clock_.now() + 0.002);
  }
}

void DriveBackend::on_deactivate() {
  for (int i = 0; i < 3; ++i) set_enable(i, false);
}

void DriveBackend::on_shutdown() noexcept {
  disable_all();
  transport_->close();
}

void DriveBackend::on_error() noexcept { disable_all(); }

void DriveBackend::on_read(double time_s, HardwareState& s) { read_axes(time_s, s); }

void DriveBackend::on_write(const HardwareCommand& cmd, double) {
  for (int i = 0; i < 3; ++i) {
    const AxisRegisters& a = map_.axes[i];
    if (cmd.mode[i] == JointMode::kPosition) {
      const auto regs = split32(theta_to_counts(a, cmd.theta_m[i]), map_.word_order);
      transport_->write(a.unit_id, a.position_command, 2, regs.data());
      if (!enable_[i]) set_enable(i, true);
    } else if (enable_[i]) {
      set_enable(i, false);
    }
  }
}

}  // namespace gpm::hw
