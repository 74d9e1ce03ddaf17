#include "hw/backends/drive_emulator.hpp"

#include "models/rng.hpp"

#include <arpa/inet.h>
#include <netdb.h>
#include <netinet/in.h>
#include <sys/select.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <vector>

#include <fmt/format.h>
#include <modbus.h>

#include "hw/hw_errors.hpp"
#include "models/errors.hpp"

namespace gpm::hw {
namespace {


bool get_bit(const std::uint16_t* regs, const RegisterBit& b) { return (regs[b.address] >> b.bit) & 1u; }

void put_bit(std::uint16_t* regs, const RegisterBit& b, bool on) {
  const auto mask = static_cast<std::uint16_t>(1u << b.bit);
  regs[b.address] = on ? static_cast<std::uint16_t>(regs[b.address] | mask)
                       : static_cast<std::uint16_t>(regs[b.address] & ~mask);
}

}  // namespace

std::string emulator_bind_address(const std::string& name, bool allow_non_loopback) {
  addrinfo hints{};
  hints.ai_family = AF_INET;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* found = nullptr;
  const int rc = ::getaddrinfo(name.c_str(), nullptr, &hints, &found);
  if (rc != 0 || !found) {
    throw InputError(fmt::format("--bind: '{}' is not an IPv4 address or a name with one ({}); "
                                 "e.g. 127.0.0.1 or localhost",
                                 name, rc != 0 ? gai_strerror(rc) : "no address"));
  }
  const in_addr a = reinterpret_cast<const sockaddr_in*>(found->ai_addr)->sin_addr;
  ::freeaddrinfo(found);
  char text[INET_ADDRSTRLEN] = {};
  ::inet_ntop(AF_INET, &a, text, sizeof text);
  const bool loopback = (ntohl(a.s_addr) >> 24) == 127;
  if (!loopback && !allow_non_loopback) {
    throw InputError(fmt::format("--bind: '{}' ({}) is not a loopback address; Modbus TCP has no "
                                 "authentication, so listening beyond this machine needs "
                                 "--allow-non-loopback",
                                 name, text));
  }
  return text;
}

void validate_emulator_options(const EmulatorOptions& o) {
  in_addr a{};
  if (::inet_pton(AF_INET, o.bind_address.c_str(), &a) != 1) {
    throw InputError(fmt::format("--bind: '{}' is not a numeric IPv4 address (resolve names with "
                                 "emulator_bind_address)",
                                 o.bind_address));
  }
  if (o.port < 0 || o.port > 65535)
    throw InputError(fmt::format("--port: {} is outside 0..65535 (0: an ephemeral port)", o.port));
  if (!(o.tick_s > 0 && o.tick_s <= 60))
    throw InputError(fmt::format("tick: {} s is outside (0, 60] s", o.tick_s));
  if (!(o.comms_watchdog_s > 0 && o.comms_watchdog_s <= 60)) {
    throw InputError(fmt::format("--comms-watchdog: {} s is outside (0, 60] s (0 would switch the "
                                 "drives off before any request)",
                                 o.comms_watchdog_s));
  }
  if (!(o.command_period_s >= 1e-4 && o.command_period_s <= 1.0))
    throw InputError(fmt::format("--command-period: {} s is outside [0.0001, 1] s (the client's command period)",
                                 o.command_period_s));
  const EmulatorFaults& f = o.faults;
  for (const auto& [flag, n] : {std::pair{"--drop-after-writes", f.drop_after_writes},
                                std::pair{"--delay-after-writes", f.delay_after_writes},
                                std::pair{"--fault-after-writes", f.fault_after_writes},
                                std::pair{"--garbage-after-writes", f.garbage_after_writes},
                                std::pair{"--slip-after-writes", f.slip_after_writes},
                                std::pair{"--stall-after-writes", f.stall_after_writes}}) {
    if (n < -1) throw InputError(fmt::format("{}: {} is not a count of writes (>= 0, or -1: never)", flag, n));
  }
  if (!(f.delay_s >= 0 && f.delay_s <= 60))
    throw InputError(fmt::format("--delay: {} s is outside [0, 60] s", f.delay_s));
  if (!(f.stall_s >= 0 && f.stall_s <= 60))
    throw InputError(fmt::format("--stall: {} s is outside [0, 60] s", f.stall_s));
  if (f.fault_axis < 0 || f.fault_axis > 2 || f.garbage_axis < 0 || f.garbage_axis > 2 || f.slip_axis < 0 ||
      f.slip_axis > 2)
    throw InputError("--fault-axis, --garbage-axis, --slip-axis: an axis is 0, 1 or 2");
  if (std::abs(f.slip_counts) > 1000000)
    throw InputError(fmt::format("--slip-counts: {} is outside +-1000000 counts", f.slip_counts));
}

constexpr double kSendTimeoutS = 0.05;  // longest wait to send one reply

struct DriveEmulator::Impl {
  modbus_t* ctx = nullptr;
  std::map<int, modbus_mapping_t*> units;
  std::vector<int> clients;
  std::array<bool, 3> power{}, armed{true, true, true}, fault{}, garbage{}, slipped{};
  Eigen::Vector3d command_theta = Eigen::Vector3d::Zero();
  std::array<JointMode, 3> command_mode{};
  double command_time = 0.0;
  bool feedforward_live = false;
  double start = 0.0, last_request = 0.0;  // on the emulator's clock (s)
  double next_tick = 0.0;                  // when the next plant tick is due
  double plant_t = 0.0;                    // stepped: the plant's time (s)
  double tick_t = 0.0;                     // the plant's time at its last tick (s): the latch's time
  bool seen_request = false;
  bool serving = false;  // started (not serve_bytes): requests bring the plant up to the clock
  long writes = 0;
  bool delaying = false, dropped = false, stalled = false;
  std::string error;
  Rng rng{12345};

  std::uint16_t* regs(int unit) { return units.at(unit)->tab_registers; }
};

DriveEmulator::DriveEmulator(const RegisterMap& map, const TwinBackendConfig& twin,
                             const EmulatorOptions& options)
    : map_(map), options_(options), clock_(options.clock ? *options.clock : steady_clock()), twin_(twin),
      impl_(std::make_unique<Impl>()) {}

bool DriveEmulator::wait_until_no_clients(double timeout_s) {
  std::unique_lock lock(mutex_);
  return clients_gone_.wait_for(lock, std::chrono::duration<double>(timeout_s),
                                [&] { return impl_->clients.empty(); });
}

void DriveEmulator::tick_now() {
  std::lock_guard lock(mutex_);
  prepare();
  const double now = clock_.now();
  tick(options_.stepped ? impl_->plant_t : now - impl_->start);
  if (impl_->serving) impl_->next_tick = std::max(impl_->next_tick, now + options_.tick_s);
}

DriveEmulator::~DriveEmulator() {
  stop();
  for (auto& [unit, m] : impl_->units) modbus_mapping_free(m);
  if (impl_->ctx) modbus_free(impl_->ctx);
}

void DriveEmulator::prepare() {
  Impl& s = *impl_;
  if (!s.units.empty()) return;
  validate_emulator_options(options_);
  // Register space per unit, large enough for every address of its axes.
  std::map<int, int> size;
  for (const AxisRegisters& a : map_.axes) {
    int hi = std::max({a.position_command + 1, a.actual_position + 1, a.status_word,
                       a.control_word, a.enable.address, a.enabled.address, a.fault.address,
                       a.actual_velocity + 1, a.actual_torque, a.fault_code, a.latched_position + 1,
                       a.latch_id});
    size[a.unit_id] = std::max(size[a.unit_id], hi + 1);
  }
  if (map_.latch)
    size[map_.latch->unit_id] = std::max({size[map_.latch->unit_id], map_.latch->address + 1,
                                          map_.latch->time_address + 2});
  if (options_.stepped && !map_.latch)
    throw InputError("--stepped: the register map has no latch (the plant steps at each latch trigger)");
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
  // After a malformed request libmodbus waits its response timeout before it
  // flushes the connection; the server is single-threaded, so keep that short
  // (the default 0.5 s stalled every client).
  modbus_set_response_timeout(s.ctx, 0, 1000);
  s.start = clock_.now();
  s.last_request = s.start;
  s.next_tick = s.start;
}

int DriveEmulator::start() {
  Impl& s = *impl_;
  prepare();
  listen_fd_ = modbus_tcp_listen(s.ctx, 8);
  if (listen_fd_ < 0) {
    throw HardwareError(fmt::format("drive emulator: cannot listen on {}:{}: {}",
                                    options_.bind_address, options_.port, modbus_strerror(errno)));
  }
  sockaddr_in addr{};
  socklen_t len = sizeof addr;
  getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&addr), &len);
  port_ = ntohs(addr.sin_port);
  tick(0.0);
  s.next_tick = s.start + options_.tick_s;
  s.serving = true;
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
  clients_gone_.notify_all();
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
      clock_.now() - s.last_request > options_.comms_watchdog_s;
  s.tick_t = t;
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
    // A slipped encoder: the drive servoes its shifted reading onto the command.
    const long slip = s.slipped[i] ? options_.faults.slip_counts : 0;
    cmd.theta_m[i] = counts_to_theta(a, static_cast<std::int64_t>(join32(r + a.position_command, map_.word_order)) -
                                            a.sign * slip);
  }
  // Stepped, every tick is one client cycle with its setpoint: the drive
  // interpolates from the setpoint before (a repeated one stands still), as
  // the twin backend's drive does at every write.
  if (options_.stepped || cmd.theta_m != s.command_theta || cmd.mode != s.command_mode) {
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
    const long slip = s.slipped[i] ? options_.faults.slip_counts : 0;
    std::array<std::uint16_t, 2> pos =
        split32(static_cast<std::int32_t>(theta_to_counts(a, st.theta_m[i]) + a.sign * slip), map_.word_order);
    if (s.garbage[i]) pos = {static_cast<std::uint16_t>(s.rng.bits()), static_cast<std::uint16_t>(s.rng.bits())};
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

void DriveEmulator::tick_if_due(double now) {
  Impl& s = *impl_;
  if (now < s.next_tick) return;
  if (!options_.stepped) {
    tick(now - s.start);
  } else {
    // Stepped: between latch triggers the plant's time stands; only what
    // switches a power stage off acts at once (the comms watchdog, an enable
    // bit cleared: a client that disables its drives and goes sees them off).
    bool off = s.seen_request && now - s.last_request > options_.comms_watchdog_s;
    for (int i = 0; i < 3; ++i) off = off || (s.power[i] && !get_bit(s.regs(map_.axes[i].unit_id), map_.axes[i].enable));
    if (off) tick(s.plant_t);
  }
  s.next_tick += options_.tick_s;
  if (s.next_tick < now) s.next_tick = now + options_.tick_s;
}

void DriveEmulator::drop_client(int fd) {
  Impl& s = *impl_;
  ::close(fd);
  s.clients.erase(std::remove(s.clients.begin(), s.clients.end(), fd), s.clients.end());
  if (s.clients.empty()) clients_gone_.notify_all();
}

bool DriveEmulator::count_write() {
  Impl& s = *impl_;
  const EmulatorFaults& f = options_.faults;
  ++s.writes;
  auto hit = [&](long after) { return after >= 0 && s.writes >= after; };
  if (hit(f.drop_after_writes)) {
    s.dropped = true;
    close_clients();
    ::close(listen_fd_);
    listen_fd_ = -1;
    return false;
  }
  if (hit(f.delay_after_writes)) s.delaying = true;
  if (hit(f.fault_after_writes)) s.fault[static_cast<size_t>(f.fault_axis)] = true;
  if (hit(f.garbage_after_writes)) s.garbage[static_cast<size_t>(f.garbage_axis)] = true;
  if (hit(f.slip_after_writes)) s.slipped[static_cast<size_t>(f.slip_axis)] = true;
  if (hit(f.stall_after_writes)) s.stalled = true;
  return true;
}

bool DriveEmulator::hold_reply() {
  Impl& s = *impl_;
  const EmulatorFaults& f = options_.faults;
  if (s.stalled) {  // swallowed: no reply, the server held for stall_s
    mutex_.unlock();
    clock_.sleep_until(clock_.now() + f.stall_s);
    mutex_.lock();
    return false;
  }
  if (s.delaying) {
    mutex_.unlock();
    clock_.sleep_until(clock_.now() + f.delay_s);
    mutex_.lock();
  }
  return true;
}

void DriveEmulator::reply(int fd, const std::uint8_t* q, int length, bool latch_write) {
  Impl& s = *impl_;
  modbus_set_socket(s.ctx, fd);
  const auto it = s.units.find(q[6]);
  if (it == s.units.end()) {
    if (modbus_reply_exception(s.ctx, q, MODBUS_EXCEPTION_GATEWAY_PATH) < 0) drop_client(fd);
    return;
  }
  if (modbus_reply(s.ctx, q, length, it->second) < 0) {  // the client does not read: dropped
    drop_client(fd);
    return;
  }
  // A write that covers the latch register (its value is in the mapping now).
  if (latch_write && map_.latch->address < it->second->nb_registers) {
    const std::uint16_t id = it->second->tab_registers[map_.latch->address];
    for (const AxisRegisters& a : map_.axes) {  // every axis at once, from the same plant tick
      std::uint16_t* r = s.regs(a.unit_id);
      r[a.latched_position] = r[a.actual_position];
      r[a.latched_position + 1] = r[a.actual_position + 1];
      r[a.latch_id] = id;
    }
    if (map_.latch->time_address >= 0) {  // the drives' time of that tick, in microseconds (wrapping)
      const auto us = static_cast<std::uint32_t>(static_cast<std::uint64_t>(std::llround(s.tick_t * 1e6)));
      const auto t = split32(static_cast<std::int32_t>(us), map_.word_order);
      std::copy(t.begin(), t.end(), s.regs(map_.latch->unit_id) + map_.latch->time_address);
    }
  }
}

void DriveEmulator::handle_request(int fd) {
  Impl& s = *impl_;
  std::uint8_t q[MODBUS_TCP_MAX_ADU_LENGTH] = {};
  modbus_set_socket(s.ctx, fd);
  const int rc = modbus_receive(s.ctx, q);
  if (rc <= 0) {
    if (rc < 0) drop_client(fd);
    return;
  }
  const double now = clock_.now();
  s.last_request = now;
  s.seen_request = true;
  // The plant as it is at the time of the request (a tick due now runs
  // first, whether or not the serving loop has come to it yet).
  const int unit = q[6], function = q[7];
  const int addr = (q[8] << 8) | q[9];
  const bool write = function == MODBUS_FC_WRITE_SINGLE_REGISTER || function == MODBUS_FC_WRITE_MULTIPLE_REGISTERS;
  const int count = function == MODBUS_FC_WRITE_SINGLE_REGISTER ? 1 : write ? ((q[10] << 8) | q[11]) : 0;
  const bool latch_write = map_.latch && unit == map_.latch->unit_id && addr <= map_.latch->address &&
                           map_.latch->address < addr + count;
  if (s.serving && !options_.stepped) {
    tick_if_due(now);
  } else if (s.serving && latch_write) {  // stepped: one client cycle
    s.plant_t += options_.command_period_s;
    tick(s.plant_t);
  }
  if (write && !count_write()) return;
  if (!hold_reply()) return;
  reply(fd, q, rc, latch_write);
}

std::string DriveEmulator::serve_bytes(std::string_view bytes, double t_s) {
  std::lock_guard lock(mutex_);
  prepare();
  int sv[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM, 0, sv) != 0) throw HardwareError("drive emulator: socketpair failed");
  // The client's end: every request, then end of stream (the client hangs up).
  size_t sent = 0;
  while (sent < bytes.size()) {
    const ssize_t n = ::send(sv[0], bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) break;
    sent += static_cast<size_t>(n);
  }
  ::shutdown(sv[0], SHUT_WR);
  impl_->clients.push_back(sv[1]);
  // Each request is read and answered; the end of the stream closes the
  // server's end (each round consumes at least one byte or ends the stream).
  auto open = [&] { return std::find(impl_->clients.begin(), impl_->clients.end(), sv[1]) != impl_->clients.end(); };
  std::string reply;
  auto take_replies = [&] {  // the client reads as it goes (a full socket would block the server)
    char buf[4096];
    for (;;) {
      const ssize_t n = ::recv(sv[0], buf, sizeof buf, MSG_DONTWAIT);
      if (n <= 0) break;
      reply.append(buf, static_cast<size_t>(n));
    }
  };
  for (size_t round = 0; round <= bytes.size() && open(); ++round) {
    handle_request(sv[1]);
    take_replies();
  }
  if (open()) {
    ::close(sv[1]);
    impl_->clients.erase(std::remove(impl_->clients.begin(), impl_->clients.end(), sv[1]), impl_->clients.end());
  }
  tick(t_s);
  take_replies();
  ::close(sv[0]);
  return reply;
}

bool DriveEmulator::request_waiting() const {
  fd_set set;
  FD_ZERO(&set);
  int maxfd = -1;
  for (int fd : impl_->clients) FD_SET(fd, &set), maxfd = std::max(maxfd, fd);
  if (maxfd < 0) return false;
  timeval none{0, 0};
  return ::select(maxfd + 1, &set, nullptr, nullptr, &none) > 0;
}

void DriveEmulator::serve() {
  Impl& s = *impl_;
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
      // Wait for a request until the next tick (at most one tick of real time,
      // so an injected clock that moves by itself is followed too).
      double wait;
      {
        std::lock_guard lock(mutex_);
        wait = std::clamp(s.next_tick - clock_.now(), 0.0, options_.tick_s);
      }
      timeval tv{0, static_cast<suseconds_t>(wait * 1e6)};
      const int n = ::select(maxfd + 1, &set, nullptr, nullptr, &tv);
      std::unique_lock lock(mutex_);
      if (n > 0) {
        if (listen_fd_ >= 0 && FD_ISSET(listen_fd_, &set)) {
          const int fd = ::accept(listen_fd_, nullptr, nullptr);
          if (fd >= 0) {
            // A client that never reads its replies fills the socket: a reply
            // that cannot be sent within kSendTimeoutS drops that client
            // instead of stalling the server (and every other client).
            const timeval limit{0, static_cast<suseconds_t>(kSendTimeoutS * 1e6)};
            ::setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &limit, sizeof limit);
            s.clients.push_back(fd);
          }
        }
        const std::vector<int> ready = s.clients;
        for (int fd : ready) {
          if (FD_ISSET(fd, &set) && std::find(s.clients.begin(), s.clients.end(), fd) != s.clients.end())
            handle_request(fd);
        }
      }
      const double now = clock_.now();
      // A request already waiting in a socket is not a lost connection: when
      // the watchdog would trip (e.g. this thread was not scheduled for a
      // while), serve what is waiting first.
      if (now >= s.next_tick && s.seen_request && now - s.last_request > options_.comms_watchdog_s &&
          request_waiting()) {
        continue;
      }
      tick_if_due(now);
    }
  } catch (const std::exception& e) {
    std::lock_guard lock(mutex_);
    s.error = e.what();
    s.power = {};
  }
}

}  // namespace gpm::hw
