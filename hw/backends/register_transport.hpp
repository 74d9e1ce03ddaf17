// Transport of 16-bit registers to and from drives, independent of the
// protocol that carries them. Modbus TCP (ModbusTransport) is one
// implementation; a CANopen CiA-402 or EtherCAT transport can be another.
#pragma once

#include <cstdint>
#include <string>

namespace gpm::hw {

class RegisterTransport {
 public:
  RegisterTransport() = default;
  virtual ~RegisterTransport() = default;
  RegisterTransport(const RegisterTransport&) = delete;
  RegisterTransport& operator=(const RegisterTransport&) = delete;

  // Opens the connection; throws HardwareError naming the address.
  virtual void connect() = 0;
  // Closes the connection; never throws.
  virtual void close() noexcept = 0;
  // Reads count registers from address of unit into out; throws HardwareError.
  virtual void read(int unit, int address, int count, std::uint16_t* out) = 0;
  // Writes count registers at address of unit; throws HardwareError.
  virtual void write(int unit, int address, int count, const std::uint16_t* values) = 0;
  // Where the transport talks to ("modbus-tcp 127.0.0.1:1502").
  virtual std::string describe() const = 0;
};

}  // namespace gpm::hw
