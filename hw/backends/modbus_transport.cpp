#include "hw/backends/modbus_transport.hpp"

#include <cerrno>

#include <fmt/format.h>
#include <modbus.h>

#include "hw/hw_errors.hpp"

namespace gpm::hw {

ModbusTransport::ModbusTransport(std::string host, int port, double response_timeout_s)
    : host_(std::move(host)), port_(port), timeout_s_(response_timeout_s) {}

ModbusTransport::~ModbusTransport() { close(); }

std::string ModbusTransport::describe() const {
  return fmt::format("modbus-tcp {}:{}", host_, port_);
}

void ModbusTransport::connect() {
  close();
  ctx_ = modbus_new_tcp(host_.c_str(), port_);
  if (!ctx_) throw HardwareError(fmt::format("{}: cannot create a Modbus context", describe()));
  const auto sec = static_cast<uint32_t>(timeout_s_);
  const auto usec = static_cast<uint32_t>((timeout_s_ - sec) * 1e6);
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

void ModbusTransport::read(int unit, int address, int count, std::uint16_t* out) {
  if (!ctx_) throw HardwareError(fmt::format("{}: not connected", describe()));
  modbus_set_slave(ctx_, unit);
  const int n = modbus_read_registers(ctx_, address, count, out);
  if (n != count) {
    const std::string why = n < 0 ? modbus_strerror(errno) : fmt::format("{} of {} registers", n, count);
    throw HardwareError(fmt::format("{}: unit {}: reading registers {}..{} failed: {}", describe(),
                                    unit, address, address + count - 1, why));
  }
}

void ModbusTransport::write(int unit, int address, int count, const std::uint16_t* values) {
  if (!ctx_) throw HardwareError(fmt::format("{}: not connected", describe()));
  modbus_set_slave(ctx_, unit);
  const int n = modbus_write_registers(ctx_, address, count, values);
  if (n != count) {
    const std::string why = n < 0 ? modbus_strerror(errno) : fmt::format("{} of {} registers", n, count);
    throw HardwareError(fmt::format("{}: unit {}: writing registers {}..{} failed: {}", describe(),
                                    unit, address, address + count - 1, why));
  }
}

}  // namespace gpm::hw
