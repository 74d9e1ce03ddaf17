// Tests of hw/backends/modbus_transport.cpp against the drive emulator on an ephemeral
// loopback port: register round trip, clear errors for a closed port and an
// unknown unit.
#include <gtest/gtest.h>

#include "hw/backends/drive_emulator.hpp"
#include "hw/hardware_config.hpp"
#include "hw/hw_errors.hpp"
#include "hw/backends/modbus_transport.hpp"

namespace gpm::hw {
namespace {

const std::string kSrc = GPM_SOURCE_DIR;

TEST(ModbusTransport, ReadsAndWritesRegisters) {
  const RegisterMap map = load_register_map(kSrc + "/hw/examples/register_map_emulator.yaml");
  DriveEmulator emu(map, twin_config_from_scenario(kSrc + "/tests/fixtures/twin_disc.yaml", 0.004), {});
  const int port = emu.start();
  ModbusTransport t("127.0.0.1", port, 0.5);
  EXPECT_EQ(t.describe(), "modbus-tcp 127.0.0.1:" + std::to_string(port));
  t.connect();
  std::uint16_t pos[2];
  t.read(2, 12, 2, pos);
  EXPECT_NEAR(counts_to_theta(map.axes[1], join32(pos, map.word_order)), 3.11, 0.05);  // joint 2 near home
  const std::uint16_t cmd[2] = {pos[0], pos[1]};
  t.write(2, 2, 2, cmd);
  std::uint16_t back[2];
  t.read(2, 2, 2, back);
  EXPECT_EQ(back[0], cmd[0]);
  EXPECT_EQ(back[1], cmd[1]);
  EXPECT_EQ(emu.writes(), 1);
  try {
    t.read(9, 0, 1, back);
    FAIL() << "unknown unit answered";
  } catch (const HardwareError& e) {
    EXPECT_NE(std::string(e.what()).find("unit 9"), std::string::npos) << e.what();
  }
}

TEST(ModbusTransport, ClosedPortIsAClearError) {
  int port = 0;
  {
    const RegisterMap map = load_register_map(kSrc + "/hw/examples/register_map_emulator.yaml");
    DriveEmulator emu(map, twin_config_from_scenario(kSrc + "/tests/fixtures/twin_disc.yaml", 0.004), {});
    port = emu.start();
  }  // stopped: nothing listens there now
  ModbusTransport t("127.0.0.1", port, 0.2);
  try {
    t.connect();
    FAIL() << "connected to a closed port";
  } catch (const HardwareError& e) {
    EXPECT_NE(std::string(e.what()).find("127.0.0.1:" + std::to_string(port) + ": cannot connect"),
              std::string::npos)
        << e.what();
  }
  std::uint16_t r;
  EXPECT_THROW(t.read(1, 0, 1, &r), HardwareError);
}

}  // namespace
}  // namespace gpm::hw
