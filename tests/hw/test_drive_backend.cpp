// Tests of hw/backends/drive_backend.cpp over an in-memory RegisterTransport (the
// drive layer does not depend on Modbus): enable bits, scaled position
// commands, readings, faults, disable on error.
#include <map>

#include <gtest/gtest.h>

#include "hw/backends/drive_backend.hpp"
#include "hw/hw_errors.hpp"
#include "hw_test_util.hpp"

namespace gpm::hw {
namespace {

const std::string kSrc = GPM_SOURCE_DIR;

// Registers in memory; a power stage turns on as soon as its enable bit is set.
struct MemoryTransport final : RegisterTransport {
  std::map<std::pair<int, int>, std::uint16_t>* regs;
  const RegisterMap* map;
  bool broken = false;
  MemoryTransport(std::map<std::pair<int, int>, std::uint16_t>* r, const RegisterMap* m) : regs(r), map(m) {}
  void connect() override {}
  void close() noexcept override {}
  void read(int unit, int address, int count, std::uint16_t* out) override {
    if (broken) throw HardwareError("memory: broken");
    for (int k = 0; k < count; ++k) out[k] = (*regs)[{unit, address + k}];
  }
  void write(int unit, int address, int count, const std::uint16_t* v) override {
    if (broken) throw HardwareError("memory: broken");
    for (int k = 0; k < count; ++k) (*regs)[{unit, address + k}] = v[k];
    for (const AxisRegisters& a : map->axes) {  // the drive: enabled follows enable
      const bool on = ((*regs)[{a.unit_id, a.enable.address}] >> a.enable.bit) & 1u;
      auto& st = (*regs)[{a.unit_id, a.enabled.address}];
      st = on ? (st | (1u << a.enabled.bit)) : (st & ~(1u << a.enabled.bit));
    }
  }
  std::string describe() const override { return "memory"; }
};

TEST(DriveBackend, EnablesCommandsAndReads) {
  const RegisterMap map = load_register_map(kSrc + "/hw/examples/register_map_emulator.yaml");
  std::map<std::pair<int, int>, std::uint16_t> regs;
  for (int i = 0; i < 3; ++i) {
    const auto c = split32(theta_to_counts(map.axes[i], 1.0 + i), map.word_order);
    regs[{i + 1, 12}] = c[0];
    regs[{i + 1, 13}] = c[1];
  }
  auto R = [&](int unit, int address) -> std::uint16_t& { return regs[std::make_pair(unit, address)]; };
  auto R32 = [&](int unit, int address) {
    const std::uint16_t two[2] = {R(unit, address), R(unit, address + 1)};
    return join32(two, map.word_order);
  };
  DriveBackend drives(map, std::make_unique<MemoryTransport>(&regs, &map), 0.004);
  drives.configure();
  EXPECT_NEAR(drives.last_state().theta_m[1], 2.0, 1e-4);
  EXPECT_EQ(R(2, 0) & 1u, 0u);  // left disabled
  drives.activate();
  EXPECT_EQ(R(2, 0) & 1u, 1u);
  // Activation commands the current position.
  EXPECT_EQ(R32(3, 2), R32(3, 12));
  HardwareCommand c = hold_command(Eigen::Vector3d(1.0, 2.5, 3.0));
  c.mode[0] = JointMode::kTorqueOff;
  drives.write(c, 0.0);
  EXPECT_EQ(R32(2, 2), theta_to_counts(map.axes[1], 2.5));
  EXPECT_EQ(R(1, 0) & 1u, 0u);  // torque off: enable cleared
  R(3, 10) |= 1u << 3;           // drive 3 faults
  R(3, 11) = 0x7500;
  const HardwareState& s = drives.read(0.004);
  EXPECT_TRUE(s.drive[2].fault);
  EXPECT_EQ(s.drive[2].fault_code, 0x7500);
  drives.emergency_stop("test");
  for (int u = 1; u <= 3; ++u) EXPECT_EQ(R(u, 0) & 1u, 0u) << u;
}

TEST(DriveBackend, TransportFailureEntersError) {
  const RegisterMap map = load_register_map(kSrc + "/hw/examples/register_map_emulator.yaml");
  std::map<std::pair<int, int>, std::uint16_t> regs;
  auto t = std::make_unique<MemoryTransport>(&regs, &map);
  MemoryTransport* raw = t.get();
  DriveBackend drives(map, std::move(t), 0.004);
  drives.configure();
  drives.activate();
  raw->broken = true;
  EXPECT_THROW(drives.read(0.0), HardwareError);
  EXPECT_EQ(drives.state(), LifecycleState::kError);
  EXPECT_EQ(drives.error_message(), "memory: broken");
}

}  // namespace
}  // namespace gpm::hw
