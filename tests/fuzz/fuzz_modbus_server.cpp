// Fuzz target for hw/backends/drive_emulator.cpp, the Modbus TCP server side: any
// byte stream from a client is answered or dropped, never crashes the
// emulator, and leaves its plant and registers consistent (every drive
// reads an angle in [0, 2 pi) after a tick).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "hw/backends/drive_emulator.hpp"
#include "hw/hardware_config.hpp"
#include "hw/backends/register_map.hpp"

namespace {

const char* kMap = R"(# the emulator map of hw/examples, with a reversed axis and an offset
connection: {host: 127.0.0.1, port: 1502, response_timeout: 0.05}
word_order: high_first
axes:
  - {unit_id: 1, control_word: 0, position_command: 2, status_word: 10, fault_code: 11,
     actual_position: 12, actual_velocity: 14, actual_torque: 16, torque_unit: 0.01, enable: {register: 0, bit: 0}, enabled: {register: 10, bit: 0},
     fault: {register: 10, bit: 3}, counts_per_rev: 131072, sign: 1, offset: 0}
  - {unit_id: 2, control_word: 0, position_command: 2, status_word: 10, fault_code: 11,
     actual_position: 12, actual_velocity: 14, actual_torque: 16, torque_unit: 0.01, enable: {register: 0, bit: 0}, enabled: {register: 10, bit: 0},
     fault: {register: 10, bit: 3}, counts_per_rev: 131072, sign: -1, offset: 1000}
  - {unit_id: 3, control_word: 0, position_command: 2, status_word: 10, fault_code: 11,
     actual_position: 12, enable: {register: 0, bit: 0}, enabled: {register: 10, bit: 0},
     fault: {register: 10, bit: 3}, counts_per_rev: 131072, sign: 1, offset: 0}
)";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const gpm::hw::TwinBackendConfig twin = [] {
    gpm::hw::TwinBackendConfig t;
    t.period_s = 0.004;
    return t;  // nominal robot, default servo and encoder
  }();
  static const gpm::hw::RegisterMap map = gpm::hw::parse_register_map(kMap, "fuzz_map.yaml");
  static double t = 0.0;
  static auto emu = std::make_unique<gpm::hw::DriveEmulator>(map, twin, gpm::hw::EmulatorOptions{});
  t += 0.001;
  emu->serve_bytes(std::string_view(reinterpret_cast<const char*>(data), size), t);
  const gpm::sim::TwinSnapshot snap = emu->snapshot();
  for (int i = 0; i < 3; ++i)
    if (!(snap.readings[i] >= 0.0 && snap.readings[i] < 2 * M_PI)) __builtin_trap();
  return 0;
}
