// Register map of the servo drives (constant model), read from YAML because
// drives differ: per axis the unit id, the holding-register addresses of the
// position command, actual position, status word, control word, the enable
// and fault bits, and the scaling (counts per revolution, sign, offset).
// Transport-independent: addresses are 16-bit register numbers, whatever
// carries them (Modbus TCP here; a CANopen or EtherCAT transport could map
// object-dictionary entries the same way).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "models/parameters.hpp"

namespace gpm::hw {

// One bit of one 16-bit register.
struct RegisterBit {
  int address = 0;
  int bit = 0;
  bool operator==(const RegisterBit&) const = default;
};

// Registers and scaling of one axis (one drive).
struct AxisRegisters {
  int unit_id = 1;             // Modbus unit (slave) id, 0..247
  int position_command = 0;    // two registers: signed 32-bit counts
  int actual_position = 0;     // two registers: signed 32-bit counts
  int actual_velocity = -1;    // two registers, signed counts/s; -1: not reported
  int actual_torque = -1;      // one register, signed, torque_unit_nm per unit; -1: none
  double torque_unit_nm = 0.01;
  int status_word = 0;         // one register
  int control_word = 0;        // one register
  int fault_code = -1;         // one register; -1: not reported
  int latched_position = -1;   // two registers: the actual position at the last latch; -1: no latch
  int latch_id = -1;           // one register: the id written by the latch that filled latched_position
  RegisterBit enable;          // set to enable the power stage (usually in the control word)
  RegisterBit enabled;         // set while the power stage is on (usually in the status word)
  RegisterBit fault;           // set while the drive is faulted (usually in the status word)
  long long counts_per_rev = 131072;
  int sign = 1;                // +1: counts grow with theta_m; -1: they fall
  long long offset_counts = 0; // counts at theta_m = 0
  bool operator==(const AxisRegisters&) const = default;
};

// A common latch (optional): writing an id to this register of this unit makes
// every drive copy its actual position, at that one instant, to its
// latched_position and the id to its latch_id (drives whose touch-probe
// inputs share one trigger, or the emulator). The three readings of a cycle
// are then of one instant even though the drives are read one after another.
// With time_address the latch also copies the drives' own time of that
// instant, in microseconds, to two registers of its unit (unsigned 32-bit,
// wrapping): a client stepping the drives (timing: stepped) checks with it
// that every cycle advances them by exactly one period.
struct LatchRegister {
  int unit_id = 1;
  int address = 0;
  int time_address = -1;  // two registers: drive time of the last latch (us); -1: none
  bool operator==(const LatchRegister&) const = default;
};

// Word order of 32-bit values in two registers.
enum class WordOrder { kHighFirst, kLowFirst };

// The whole map and where the drives are.
struct RegisterMap {
  std::string host = "127.0.0.1";  // the drives' address (an IPv4 literal, no names)
  int port = 502;
  double response_timeout_s = 0.05;
  WordOrder word_order = WordOrder::kHighFirst;
  std::array<AxisRegisters, kNumChains> axes{};
  std::optional<LatchRegister> latch;  // with it every axis has latched_position and latch_id
  bool operator==(const RegisterMap&) const = default;
};

// Loads and validates a register map file; throws InputError with the key path.
RegisterMap load_register_map(const std::string& path);

// Parses register map YAML text (file names the source in errors).
RegisterMap parse_register_map(const std::string& text, const std::string& file);

// YAML text of a map (loads back to the same map).
std::string register_map_to_yaml(const RegisterMap& map);

// Encoder reading (rad, wrapped to [0, 2 pi)) from position counts.
double counts_to_theta(const AxisRegisters& axis, std::int64_t counts);

// Position counts for a command theta_m (rad; not wrapped). Throws
// HardwareError if it does not fit in 32 bits.
std::int32_t theta_to_counts(const AxisRegisters& axis, double theta_m);

// Splits a signed 32-bit value into two registers in the given order.
std::array<std::uint16_t, 2> split32(std::int32_t v, WordOrder order);

// Joins two registers into a signed 32-bit value.
std::int32_t join32(const std::uint16_t* regs, WordOrder order);

}  // namespace gpm::hw
