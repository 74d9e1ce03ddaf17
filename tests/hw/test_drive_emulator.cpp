// Tests of hw/drive_emulator.cpp: loopback-only ephemeral ports, power stage
// on a rising enable edge, off on the drive-side comms watchdog and on a fault.
#include <thread>

#include <arpa/inet.h>
#include <netinet/in.h>

#include <gtest/gtest.h>

#include "hw/drive_emulator.hpp"
#include "hw/hardware_config.hpp"
#include "hw/modbus_transport.hpp"

namespace gpm::hw {
namespace {

const std::string kSrc = GPM_SOURCE_DIR;

std::unique_ptr<DriveEmulator> make(const EmulatorOptions& o = {}) {
  const RegisterMap map = load_register_map(kSrc + "/hw/examples/register_map_emulator.yaml");
  return std::make_unique<DriveEmulator>(
      map, twin_config_from_scenario(kSrc + "/scenarios/simulate_disc.yaml", 0.004), o);
}

void settle_ticks() { std::this_thread::sleep_for(std::chrono::milliseconds(30)); }

TEST(DriveEmulator, EphemeralPortsDifferAndListenOnLoopbackByDefault) {
  EXPECT_EQ(EmulatorOptions{}.bind_address, "127.0.0.1");
  auto a = make(), b = make();
  const int pa = a->start(), pb = b->start();
  EXPECT_GT(pa, 0);
  EXPECT_NE(pa, pb);
}

TEST(DriveEmulator, EnableEdgeWatchdogAndFault) {
  EmulatorOptions o;
  o.comms_watchdog_s = 0.15;
  o.faults.fault_after_writes = 5;
  o.faults.fault_axis = 0;
  auto emu = make(o);
  const int port = emu->start();
  ModbusTransport t("127.0.0.1", port, 0.5);
  t.connect();
  const std::uint16_t on = 1, off = 0;
  t.write(2, 0, 1, &on);  // write 1
  settle_ticks();
  EXPECT_EQ(emu->power_on(), (std::array<bool, 3>{false, true, false}));
  // Silence longer than the comms watchdog: the drive switches itself off ...
  std::this_thread::sleep_for(std::chrono::milliseconds(250));
  EXPECT_EQ(emu->power_on(), (std::array<bool, 3>{false, false, false}));
  // ... and stays off although the enable bit is still set, until a new edge.
  std::uint16_t st = 0;
  t.read(2, 10, 1, &st);
  EXPECT_EQ(st & 1u, 0u);
  t.write(2, 0, 1, &off);  // write 2
  settle_ticks();          // the drive samples its control word every tick
  t.write(2, 0, 1, &on);   // write 3
  settle_ticks();
  EXPECT_TRUE(emu->power_on()[1]);
  t.write(1, 0, 1, &on);   // write 4
  t.write(1, 0, 1, &on);   // write 5: fault on axis 0
  settle_ticks();
  t.read(1, 10, 1, &st);
  EXPECT_EQ(st & (1u << 3), 1u << 3);
  std::uint16_t code = 0;
  t.read(1, 11, 1, &code);
  EXPECT_EQ(code, 0x2310);
  EXPECT_FALSE(emu->power_on()[0]);
}

}  // namespace
}  // namespace gpm::hw
