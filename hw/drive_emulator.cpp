#include "hw/drive_emulator.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/select.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <random>
#include <vector>

#include <fmt/format.h>
#include <modbus.h>

#include "hw/hw_errors.hpp"

namespace gpm::hw {
namespace {

using Clock = std::chrono::steady_clock;

bool get_bit(const std::uint16_t* regs, const RegisterBit& b) { return (regs[b.address] >> b.bit) & 1u; }

void put_bit(std::uint16_t* regs, const RegisterBit& b, bool on) {
  const auto mask = static_cast<std::uint16_t>(1u << b.bit);
  regs[b.address] = on ? static_cast<std::uint16_t>(regs[b.address] | mask)
                       : static_cast<std::uint16_t>(regs[b.address] & ~mask);
}

}  // namespace

struct DriveEmulator::Impl {
  modbus_t* ctx = nullptr;
  std::map<int, modbus_mapping_t*> units;
  std::vector<int> clients;
  std::array<bool, 3> power{}, armed{true, true, true}, fault{}, garbage{};
  Eigen::Vector3d command_theta = Eigen::Vector3d::Zero();
  std::array<JointMode, 3> command_mode{};
  double command_time = 0.0;
  bool feedforward_live = false;
  Clock::time_point start, last_request;
  bool seen_request = false;
  long writes = 0;
  bool delaying = false, dropped = false;
  std::string error;
  std::mt19937 rng{12345};

  std::uint16_t* regs(int unit) { return units.at(unit)->tab_registers; }
};

DriveEmulator::DriveEmulator(const RegisterMap& map, const TwinBackendConfig& twin,
                             const EmulatorOptions& options)
    : map_(map), options_(options), twin_(twin), impl_(std::make_unique<Impl>()) {}

DriveEmulator::~DriveEmulator() {
  stop();
  for (auto& [unit, m] : impl_->units) modbus_mapping_free(m);
  if (impl_->ctx) modbus_free(impl_->ctx);
}

int DriveEmulator::start() {
  Impl& s = *impl_;
  // Register space per unit, large enough for every address of its axes.
  std::map<int, int> size;
  for (const AxisRegisters& a : map_.axes) {
    int hi = std::max({a.position_command + 1, a.actual_position + 1, a.status_word,
                       a.control_word, a.enable.address, a.enabled.address, a.fault.address,
                       a.actual_velocity + 1, a.actual_torque, a.fault_code});
    size[a.unit_id] = std::max(size[a.unit_id], hi + 1);
  }
  for (auto [unit, n] : size) s.units[unit] = modbus_mapping_new(0, 0, n, 0);
  twin_.configure();
  twin_.activate();
  const HardwareState& st = twin_.last_state();
  for (int i = 0; i < 3; ++i) {
    const AxisRegisters& a = map_.axes[i];
    const auto c = split32(theta_to_counts(a, st.theta_m[i]), map_.word_order);
    std::copy(c.begin(), c.end(), s.regs(a.unit_id) + a.position_command);
    s.command_theta[i] = st.theta_m[i];
  }
  s.ctx = modbus_new_tcp(options_.bind_address.c_str(), options_.port);
  if (!s.ctx) throw HardwareError("drive emulator: cannot create a Modbus context");
  listen_fd_ = modbus_tcp_listen(s.ctx, 8);
  if (listen_fd_ < 0) {
    throw HardwareError(fmt::format("drive emulator: cannot listen on {}:{}: {}",
                                    options_.bind_address, options_.port, modbus_strerror(errno)));
  }
  sockaddr_in addr{};
  socklen_t len = sizeof addr;
  getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&addr), &len);
  port_ = ntohs(addr.sin_port);
  s.start = Clock::now();
  s.last_request = s.start;
  tick(0.0);
  thread_ = std::thread([this] { serve(); });
  return port_;
}

void DriveEmulator::stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
  close_clients();
  if (listen_fd_ >= 0) ::close(listen_fd_);
  listen_fd_ = -1;
}

void DriveEmulator::close_clients() {
  for (int fd : impl_->clients) ::close(fd);
  impl_->clients.clear();
}

std::array<bool, 3> DriveEmulator::power_on() const {
  std::lock_guard lock(mutex_);
  return impl_->power;
}

long DriveEmulator::writes() const {
  std::lock_guard lock(mutex_);
  return impl_->writes;
}

sim::TwinSnapshot DriveEmulator::snapshot() const {
  std::lock_guard lock(mutex_);
  return twin_.snapshot();
}

std::string DriveEmulator::error() const {
  std::lock_guard lock(mutex_);
  return impl_->error;
}

void DriveEmulator::tick(double t) {
  Impl& s = *impl_;
  const bool comms_lost =
      s.seen_request &&
      std::chrono::duration<double>(Clock::now() - s.last_request).count() > options_.comms_watchdog_s;
  HardwareCommand cmd;
  for (int i = 0; i < 3; ++i) {
    const AxisRegisters& a = map_.axes[i];
    std::uint16_t* r = s.regs(a.unit_id);
    const bool enable = get_bit(r, a.enable);
    if (!enable) {
      s.power[i] = false;
      s.armed[i] = true;
    } else if (s.armed[i] && !s.fault[i] && !comms_lost) {
      s.power[i] = true;  // rising edge of enable
      s.armed[i] = false;
    }
    if (s.fault[i] || comms_lost) s.power[i] = false;
    cmd.mode[i] = s.power[i] ? JointMode::kPosition : JointMode::kTorqueOff;
    cmd.theta_m[i] = counts_to_theta(a, join32(r + a.position_command, map_.word_order));
  }
  if (cmd.theta_m != s.command_theta || cmd.mode != s.command_mode) {
    twin_.write(cmd, t);
    s.command_theta = cmd.theta_m;
    s.command_mode = cmd.mode;
    s.command_time = t;
    s.feedforward_live = true;
  } else if (s.feedforward_live && t - s.command_time > 1.5 * twin_.period_s()) {
    // No new setpoint for a command period: the target stands still, so the
    // velocity feed-forward drops to zero (as a drive's setpoint interpolator does).
    twin_.write(cmd, t);
    s.feedforward_live = false;
  }
  const HardwareState& st = twin_.read(t);
  for (int i = 0; i < 3; ++i) {
    const AxisRegisters& a = map_.axes[i];
    std::uint16_t* r = s.regs(a.unit_id);
    std::array<std::uint16_t, 2> pos = split32(theta_to_counts(a, st.theta_m[i]), map_.word_order);
    if (s.garbage[i]) pos = {static_cast<std::uint16_t>(s.rng()), static_cast<std::uint16_t>(s.rng())};
    std::copy(pos.begin(), pos.end(), r + a.actual_position);
    if (a.actual_velocity >= 0) {
      const double cps = a.sign * st.velocity[i] / (2.0 * M_PI) * static_cast<double>(a.counts_per_rev);
      const auto v = split32(static_cast<std::int32_t>(std::lround(cps)), map_.word_order);
      std::copy(v.begin(), v.end(), r + a.actual_velocity);
    }
    if (a.actual_torque >= 0) {
      const long tq = std::clamp(std::lround(a.sign * st.torque[i] / a.torque_unit_nm), -32768L, 32767L);
      r[a.actual_torque] = static_cast<std::uint16_t>(static_cast<std::int16_t>(tq));
    }
    put_bit(r, a.enabled, s.power[i]);
    put_bit(r, a.fault, s.fault[i]);
    if (a.fault_code >= 0) r[a.fault_code] = s.fault[i] ? options_.faults.fault_code : 0;
  }
}

void DriveEmulator::handle_request(int fd) {
  Impl& s = *impl_;
  std::uint8_t q[MODBUS_TCP_MAX_ADU_LENGTH];
  modbus_set_socket(s.ctx, fd);
  const int rc = modbus_receive(s.ctx, q);
  if (rc <= 0) {
    if (rc < 0) {
      ::close(fd);
      s.clients.erase(std::remove(s.clients.begin(), s.clients.end(), fd), s.clients.end());
    }
    return;
  }
  s.last_request = Clock::now();
  s.seen_request = true;
  const int unit = q[6], function = q[7];
  const EmulatorFaults& f = options_.faults;
  if (function == MODBUS_FC_WRITE_SINGLE_REGISTER || function == MODBUS_FC_WRITE_MULTIPLE_REGISTERS) {
    ++s.writes;
    auto hit = [&](long after) { return after >= 0 && s.writes >= after; };
    if (hit(f.drop_after_writes)) {
      s.dropped = true;
      close_clients();
      ::close(listen_fd_);
      listen_fd_ = -1;
      return;
    }
    if (hit(f.delay_after_writes)) s.delaying = true;
    if (hit(f.fault_after_writes)) s.fault[static_cast<size_t>(f.fault_axis)] = true;
    if (hit(f.garbage_after_writes)) s.garbage[static_cast<size_t>(f.garbage_axis)] = true;
  }
  if (s.delaying) {
    mutex_.unlock();
    std::this_thread::sleep_for(std::chrono::duration<double>(f.delay_s));
    mutex_.lock();
  }
  modbus_set_socket(s.ctx, fd);
  const auto it = s.units.find(unit);
  if (it == s.units.end()) {
    modbus_reply_exception(s.ctx, q, MODBUS_EXCEPTION_GATEWAY_PATH);
  } else {
    modbus_reply(s.ctx, q, rc, it->second);
  }
}

void DriveEmulator::serve() {
  Impl& s = *impl_;
  auto next_tick = Clock::now();
  const auto period =
      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(options_.tick_s));
  try {
    while (!stop_) {
      fd_set set;
      FD_ZERO(&set);
      int maxfd = -1;
      {
        std::lock_guard lock(mutex_);
        if (listen_fd_ >= 0) FD_SET(listen_fd_, &set), maxfd = listen_fd_;
        for (int fd : s.clients) FD_SET(fd, &set), maxfd = std::max(maxfd, fd);
      }
      const auto wait = std::max(next_tick - Clock::now(), Clock::duration::zero());
      timeval tv{0, static_cast<suseconds_t>(std::chrono::duration_cast<std::chrono::microseconds>(wait).count())};
      const int n = ::select(maxfd + 1, &set, nullptr, nullptr, &tv);
      std::unique_lock lock(mutex_);
      if (n > 0) {
        if (listen_fd_ >= 0 && FD_ISSET(listen_fd_, &set)) {
          const int fd = ::accept(listen_fd_, nullptr, nullptr);
          if (fd >= 0) s.clients.push_back(fd);
        }
        const std::vector<int> ready = s.clients;
        for (int fd : ready) {
          if (FD_ISSET(fd, &set) && std::find(s.clients.begin(), s.clients.end(), fd) != s.clients.end())
            handle_request(fd);
        }
      }
      if (Clock::now() >= next_tick) {
        tick(std::chrono::duration<double>(Clock::now() - s.start).count());
        next_tick += period;
        if (next_tick < Clock::now()) next_tick = Clock::now() + period;
      }
    }
  } catch (const std::exception& e) {
    std::lock_guard lock(mutex_);
    s.error = e.what();
    s.power = {};
  }
}

}  // namespace gpm::hw
