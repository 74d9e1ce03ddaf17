// Modbus TCP register transport through libmodbus (holding registers,
// functions 3 and 16). Connects only to the one address it is given.
#pragma once

#include <string>

#include "hw/backends/register_transport.hpp"

struct _modbus;

namespace gpm::hw {

class ModbusTransport final : public RegisterTransport {
 public:
  // A transport to host:port (IPv4 literal) with a response timeout (s).
  ModbusTransport(std::string host, int port, double response_timeout_s);
  ~ModbusTransport() override;

  void connect() override;
  void close() noexcept override;
  void read(int unit, int address, int count, std::uint16_t* out) override;
  void write(int unit, int address, int count, const std::uint16_t* values) override;
  std::string describe() const override;

 private:
  std::string host_;
  int port_;
  double timeout_s_;
  _modbus* ctx_ = nullptr;
};

}  // namespace gpm::hw
