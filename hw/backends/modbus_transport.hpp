// Modbus TCP register transport (holding registers, functions 3 and 16).
// Connects only to the one address it is given. libmodbus opens the
// connection; each request is framed and its reply awaited here, so that the
// response timeout is measured on the injected clock: on the wall clock
// (production) it is the response timeout as before; on a test's ManualClock
// a reply is late when the clock has passed the deadline (e.g. moved by a
// stalled emulator), whatever the wall time, and the wall clock only bounds a
// wait for a reply that never comes (kWallBackstopS).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "hw/backends/register_transport.hpp"
#include "hw/clock.hpp"

struct _modbus;

namespace gpm::hw {

class ModbusTransport final : public RegisterTransport {
 public:
  // With an injected clock other than the wall clock, the longest wall time a
  // request waits for its reply before it is called lost (a generous bound:
  // the injected clock decides, this only ends a wait nothing would end).
  static constexpr double kWallBackstopS = 10.0;

  // A transport to host:port (IPv4 literal) with a response timeout (s) on clock.
  ModbusTransport(std::string host, int port, double response_timeout_s, Clock& clock = steady_clock());
  ~ModbusTransport() override;

  void connect() override;
  void close() noexcept override;
  void read(int unit, int address, int count, std::uint16_t* out) override;
  void write(int unit, int address, int count, const std::uint16_t* values) override;
  std::string describe() const override;

 private:
  // Sends one request PDU (function and data) to unit and returns the reply
  // PDU; throws HardwareError (what: "reading registers a..b") on a timeout,
  // a lost connection, a malformed reply or an exception reply. A late reply
  // to an earlier request (another transaction id) is read and dropped.
  std::vector<std::uint8_t> transact(int unit, const std::vector<std::uint8_t>& pdu, const std::string& what);
  [[noreturn]] void fail(int unit, const std::string& what, const std::string& why) const;

  std::string host_;
  int port_;
  double timeout_s_;
  Clock& clock_;
  _modbus* ctx_ = nullptr;
  std::uint16_t transaction_ = 0;
};

}  // namespace gpm::hw
