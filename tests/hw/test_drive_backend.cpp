// Tests of hw/backends/drive_backend.cpp over an in-memory RegisterTransport (the
// drive layer does not depend on Modbus): enable bits, scaled position
// commands, readings, faults, disable on error, readings latched at one
// instant; stepped timing: the latch's time checked every cycle, the enable
// wait counted in the drives' cycles.
#include <functional>
#include <map>

#include <gtest/gtest.h>

#include "hw/backends/drive_backend.hpp"
#include "hw/clock.hpp"
#include "hw/hw_errors.hpp"
#include "hw_test_util.hpp"

namespace gpm::hw {
namespace {

const std::string kSrc = GPM_SOURCE_DIR;

// Registers in memory; a power stage turns on as soon as its enable bit is
// set; a write to the map's latch register copies every actual position to
// its latched position (unless latching is off: a drive that misses it).
struct MemoryTransport final : RegisterTransport {
  std::map<std::pair<int, int>, std::uint16_t>* regs;
  const RegisterMap* map;
  bool broken = false;
  bool latching = true;
  bool powers_on = true;  // false: a power stage that never reports enabled
  std::uint32_t latch_step_us = 0;  // each latch advances the latch's time (map with latch.time) by this
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
    const bool latch = map->latch && unit == map->latch->unit_id && address <= map->latch->address &&
                       map->latch->address < address + count;
    if (latch && latching && map->latch->time_address >= 0) {  // the drives' time of the latch
      const int t = map->latch->time_address;
      std::uint16_t* hi = &(*regs)[{map->latch->unit_id, t}];
      const std::uint32_t us = ((static_cast<std::uint32_t>(*hi) << 16) | (*regs)[{map->latch->unit_id, t + 1}]) +
                               latch_step_us;
      (*regs)[{map->latch->unit_id, t}] = static_cast<std::uint16_t>(us >> 16);
      (*regs)[{map->latch->unit_id, t + 1}] = static_cast<std::uint16_t>(us & 0xffffu);
    }
    for (const AxisRegisters& a : map->axes) {
      if (!latch || !latching) continue;
      (*regs)[{a.unit_id, a.latched_position}] = (*regs)[{a.unit_id, a.actual_position}];
      (*regs)[{a.unit_id, a.latched_position + 1}] = (*regs)[{a.unit_id, a.actual_position + 1}];
      (*regs)[{a.unit_id, a.latch_id}] = v[map->latch->address - address];
    }
    for (const AxisRegisters& a : map->axes) {  // the drive: enabled follows enable
      const bool on = powers_on && (((*regs)[{a.unit_id, a.enable.address}] >> a.enable.bit) & 1u);
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

// Power stages that never report enabled: activation gives up after 1 s on
// the injected clock (no wall-clock wait) with one error naming it.
TEST(DriveBackend, EnableTimeoutRunsOnTheInjectedClock) {
  const RegisterMap map = load_register_map(kSrc + "/hw/examples/register_map_emulator.yaml");
  std::map<std::pair<int, int>, std::uint16_t> regs;
  auto t = std::make_unique<MemoryTransport>(&regs, &map);
  t->powers_on = false;
  ManualClock clock;
  DriveBackend drives(map, std::move(t), 0.004, clock);
  drives.configure();
  const double t0 = clock.now();
  try {
    drives.activate();
    ADD_FAILURE() << "activated without enabled drives";
  } catch (const HardwareError& e) {
    EXPECT_NE(std::string(e.what()).find("did not report enabled within 1 s"), std::string::npos) << e.what();
  }
  EXPECT_GE(clock.now() - t0, 1.0);
  EXPECT_LT(clock.now() - t0, 1.01);
  EXPECT_GT(clock.waits(), 100);  // it polled on the clock, 2 ms apart
}

// With a latch the readings are the positions of the latch instant: a drive
// whose position changes after the latch (the robot moves on while the
// drives are read one by one) still reads the latched value; a drive that
// missed the latch (its latch id is not this cycle's) is an error, not a
// reading of another instant.
TEST(DriveBackend, ReadsTheLatchedPositionsOfOneInstant) {
  const RegisterMap map = load_register_map(kSrc + "/hw/examples/register_map_emulator.yaml");
  ASSERT_TRUE(map.latch.has_value());
  std::map<std::pair<int, int>, std::uint16_t> regs;
  auto set_position = [&](int axis, double theta) {
    const auto c = split32(theta_to_counts(map.axes[axis], theta), map.word_order);
    regs[{map.axes[axis].unit_id, map.axes[axis].actual_position}] = c[0];
    regs[{map.axes[axis].unit_id, map.axes[axis].actual_position + 1}] = c[1];
  };
  for (int i = 0; i < 3; ++i) set_position(i, 1.0 + i);
  auto t = std::make_unique<MemoryTransport>(&regs, &map);
  MemoryTransport* raw = t.get();
  DriveBackend drives(map, std::move(t), 0.004);
  drives.configure();
  EXPECT_NEAR(drives.last_state().theta_m[2], 3.0, 1e-4);
  // The robot moves on between the latch and the reads: the reads give the latch instant.
  struct MovingTransport final : RegisterTransport {
    MemoryTransport* inner;
    std::function<void()> after_latch;
    explicit MovingTransport(MemoryTransport* m) : inner(m) {}
    void connect() override {}
    void close() noexcept override {}
    void read(int u, int a, int n, std::uint16_t* out) override { inner->read(u, a, n, out); }
    void write(int u, int a, int n, const std::uint16_t* v) override {
      inner->write(u, a, n, v);
      const LatchRegister& l = *inner->map->latch;
      if (u == l.unit_id && a <= l.address && l.address < a + n) after_latch();
    }
    std::string describe() const override { return "moving"; }
  };
  auto moving = std::make_unique<MovingTransport>(raw);
  moving->after_latch = [&] { for (int i = 0; i < 3; ++i) set_position(i, 1.5 + i); };
  DriveBackend latched(map, std::move(moving), 0.004);
  for (int i = 0; i < 3; ++i) set_position(i, 1.0 + i);
  latched.configure();
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(latched.last_state().theta_m[i], 1.0 + i, 1e-4) << i;
  // A drive that misses the latch: its old latch id is refused.
  raw->latching = false;
  EXPECT_THROW(drives.read(0.004), HardwareError);
}

// Stepped: power stages that never report enabled are given up after 1 s of
// the drives' cycles (250 reads at 4 ms), not of the clock, which never moves;
// the latch's time is read from its own unit when no axis is there, and a
// drive time that does not step by the period (here: a missed latch time)
// stops the drives.
TEST(DriveBackend, SteppedCountsTheDrivesCyclesAndChecksTheirTime) {
  RegisterMap map = load_register_map(kSrc + "/hw/examples/register_map_emulator.yaml");
  map.latch->unit_id = 9;  // a unit of its own (no axis)
  map.latch->time_address = 40;
  std::map<std::pair<int, int>, std::uint16_t> regs;
  auto t = std::make_unique<MemoryTransport>(&regs, &map);
  MemoryTransport* raw = t.get();
  raw->latch_step_us = 4000;
  raw->powers_on = false;
  ManualClock clock;
  DriveBackend drives(map, std::move(t), 0.004, clock, DriveTiming::kStepped);
  EXPECT_TRUE(drives.simulated_time());
  drives.configure();
  auto latch_us = [&] { return (static_cast<std::uint32_t>(regs[{9, 40}]) << 16) | regs[{9, 41}]; };
  const std::uint32_t before = latch_us();
  try {
    drives.activate();
    ADD_FAILURE() << "activated without enabled drives";
  } catch (const HardwareError& e) {
    EXPECT_NE(std::string(e.what()).find("did not report enabled within 1 s"), std::string::npos) << e.what();
  }
  const std::uint32_t reads = (latch_us() - before) / 4000;  // one latch per read
  EXPECT_GE(reads, 250u);
  EXPECT_LE(reads, 251u);
  EXPECT_EQ(clock.now(), 0.0);
  EXPECT_EQ(clock.waits(), 0);
  // Enabled drives, then a latch whose time does not move: refused, drives off.
  std::map<std::pair<int, int>, std::uint16_t> regs2;
  auto t2 = std::make_unique<MemoryTransport>(&regs2, &map);
  MemoryTransport* raw2 = t2.get();
  raw2->latch_step_us = 4000;
  DriveBackend ok(map, std::move(t2), 0.004, clock, DriveTiming::kStepped);
  ok.configure();
  ok.activate();
  EXPECT_NO_THROW(ok.read(0.004));
  raw2->latch_step_us = 0;
  try {
    ok.read(0.008);
    ADD_FAILURE() << "a latch time that did not step was accepted";
  } catch (const HardwareError& e) {
    EXPECT_NE(std::string(e.what()).find("advanced by 0.000 ms in one cycle"), std::string::npos) << e.what();
  }
  EXPECT_EQ(ok.state(), LifecycleState::kError);
  for (const AxisRegisters& a : map.axes) {  // every enable bit cleared
    const std::pair<int, int> at{a.unit_id, a.enable.address};
    EXPECT_EQ(regs2[at] & 1u, 0u) << a.unit_id;
  }
}

}  // namespace
}  // namespace gpm::hw
