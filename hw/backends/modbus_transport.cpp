#include "hw/backends/modbus_transport.hpp"

#include <poll.h>
#include <sys/socket.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>

#include <fmt/format.h>
#include <modbus.h>

#include "hw/hw_errors.hpp"

namespace gpm::hw {
namespace {

double wall_now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

constexpr double kSliceS = 0.005;  // on an injected clock: look at it this often while waiting

}  // namespace

ModbusTransport::ModbusTransport(std::string host, int port, double response_timeout_s, Clock& clock)
    : host_(std::move(host)), port_(port), timeout_s_(response_timeout_s), clock_(clock) {}

ModbusTransport::~ModbusTransport() { close(); }

std::string ModbusTransport::describe() const {
  return fmt::format("modbus-tcp {}:{}", host_, port_);
}

void ModbusTransport::connect() {
  close();
  ctx_ = modbus_new_tcp(host_.c_str(), port_);
  if (!ctx_) throw HardwareError(fmt::format("{}: cannot create a Modbus context", describe()));
  // libmodbus's timeouts bound the connect only; replies are awaited in transact().
  const double t = &clock_ == &steady_clock() ? timeout_s_ : std::max(timeout_s_, kWallBackstopS);
  const auto sec = static_cast<uint32_t>(t);
  const auto usec = static_cast<uint32_t>((t - sec) * 1e6);
  modbus_set_response_timeout(ctx_, sec, usec);
  modbus_set_byte_timeout(ctx_, sec, usec);
  modbus_set_error_recovery(ctx_, MODBUS_ERROR_RECOVERY_NONE);
  if (modbus_connect(ctx_) == -1) {
    const std::string why = modbus_strerror(errno);
    close();
    throw HardwareError(fmt::format("{}: cannot connect: {}", describe(), why));
  }
}

void ModbusTransport::close() noexcept {
  if (!ctx_) return;
  modbus_close(ctx_);
  modbus_free(ctx_);
  ctx_ = nullptr;
}

void ModbusTransport::fail(int unit, const std::string& what, const std::string& why) const {
  throw HardwareError(fmt::format("{}: unit {}: {} failed: {}", describe(), unit, what, why));
}

std::vector<std::uint8_t> ModbusTransport::transact(int unit, const std::vector<std::uint8_t>& pdu,
                                                   const std::string& what) {
  if (!ctx_) throw HardwareError(fmt::format("{}: not connected", describe()));
  const int fd = modbus_get_socket(ctx_);
  const bool wall = &clock_ == &steady_clock();
  const double deadline = clock_.now() + timeout_s_;
  const double wall_deadline = wall_now() + (wall ? timeout_s_ : std::max(timeout_s_, kWallBackstopS));
  const std::uint16_t tid = ++transaction_;
  // MBAP header: transaction id, protocol 0, length (unit + PDU), unit.
  std::vector<std::uint8_t> adu{static_cast<std::uint8_t>(tid >> 8), static_cast<std::uint8_t>(tid & 0xff), 0, 0,
                                static_cast<std::uint8_t>((pdu.size() + 1) >> 8),
                                static_cast<std::uint8_t>((pdu.size() + 1) & 0xff), static_cast<std::uint8_t>(unit)};
  adu.insert(adu.end(), pdu.begin(), pdu.end());
  for (size_t sent = 0; sent < adu.size();) {
    const ssize_t n = ::send(fd, adu.data() + sent, adu.size() - sent, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail(unit, what, modbus_strerror(errno));
    sent += static_cast<size_t>(n);
  }
  // Reads exactly n bytes; a late reply is a timeout (on the injected clock,
  // or past the wall bound).
  auto receive = [&](std::uint8_t* out, size_t n) {
    for (size_t got = 0; got < n;) {
      const double left = deadline - clock_.now();
      const double wall_left = wall_deadline - wall_now();
      if (left <= 0 || wall_left <= 0) fail(unit, what, modbus_strerror(ETIMEDOUT));
      const double wait = wall ? std::min(left, wall_left) : std::min(kSliceS, wall_left);
      pollfd p{fd, POLLIN, 0};
      const int r = ::poll(&p, 1, static_cast<int>(std::ceil(wait * 1000)));
      if (r < 0 && errno == EINTR) continue;
      if (r < 0) fail(unit, what, modbus_strerror(errno));
      if (r == 0) continue;
      const ssize_t k = ::recv(fd, out + got, n - got, 0);
      if (k < 0 && (errno == EINTR || errno == EAGAIN)) continue;
      if (k == 0) fail(unit, what, "connection closed by the drive");
      if (k < 0) fail(unit, what, modbus_strerror(errno));
      got += static_cast<size_t>(k);
    }
    // A reply that came in after the deadline (the clock moved while it
    // travelled) is late too.
    if (clock_.now() > deadline) fail(unit, what, modbus_strerror(ETIMEDOUT));
  };
  for (;;) {
    std::uint8_t head[7];
    receive(head, 7);
    const size_t len = (static_cast<size_t>(head[4]) << 8) | head[5];
    if (head[2] != 0 || head[3] != 0 || len < 2 || len > MODBUS_TCP_MAX_ADU_LENGTH - 6)
      fail(unit, what, "malformed reply header");
    std::vector<std::uint8_t> reply(len - 1);
    receive(reply.data(), reply.size());
    const std::uint16_t got = static_cast<std::uint16_t>((head[0] << 8) | head[1]);
    if (got != tid) continue;  // the late reply to an earlier request: dropped
    if (head[6] != unit) fail(unit, what, fmt::format("reply from unit {}", head[6]));
    if (reply[0] == (pdu[0] | 0x80)) {
      fail(unit, what, reply.size() >= 2 ? modbus_strerror(MODBUS_ENOBASE + reply[1]) : "exception");
    }
    if (reply[0] != pdu[0]) fail(unit, what, fmt::format("reply of function {}", reply[0]));
    return reply;
  }
}

void ModbusTransport::read(int unit, int address, int count, std::uint16_t* out) {
  const std::string what = fmt::format("reading registers {}..{}", address, address + count - 1);
  const std::vector<std::uint8_t> pdu{MODBUS_FC_READ_HOLDING_REGISTERS, static_cast<std::uint8_t>(address >> 8),
                                      static_cast<std::uint8_t>(address & 0xff), static_cast<std::uint8_t>(count >> 8),
                                      static_cast<std::uint8_t>(count & 0xff)};
  const std::vector<std::uint8_t> r = transact(unit, pdu, what);
  if (r.size() < 2 || r[1] != 2 * count || r.size() != 2 + static_cast<size_t>(2 * count))
    fail(unit, what, fmt::format("{} of {} registers", r.size() >= 2 ? r[1] / 2 : 0, count));
  for (int i = 0; i < count; ++i)
    out[i] = static_cast<std::uint16_t>((r[2 + 2 * static_cast<size_t>(i)] << 8) | r[3 + 2 * static_cast<size_t>(i)]);
}

void ModbusTransport::write(int unit, int address, int count, const std::uint16_t* values) {
  const std::string what = fmt::format("writing registers {}..{}", address, address + count - 1);
  std::vector<std::uint8_t> pdu{MODBUS_FC_WRITE_MULTIPLE_REGISTERS, static_cast<std::uint8_t>(address >> 8),
                                static_cast<std::uint8_t>(address & 0xff), static_cast<std::uint8_t>(count >> 8),
                                static_cast<std::uint8_t>(count & 0xff), static_cast<std::uint8_t>(2 * count)};
  for (int i = 0; i < count; ++i) {
    pdu.push_back(static_cast<std::uint8_t>(values[i] >> 8));
    pdu.push_back(static_cast<std::uint8_t>(values[i] & 0xff));
  }
  const std::vector<std::uint8_t> r = transact(unit, pdu, what);
  if (r.size() != 5 || ((r[1] << 8) | r[2]) != address || ((r[3] << 8) | r[4]) != count)
    fail(unit, what, "the reply names other registers");
}

}  // namespace gpm::hw
