// The section-2.4 procedure unchanged on backend `modbus` through
// gpm-drive-emulator (loopback, ephemeral port, one stepped clock for the
// client and the emulator, so no wall-clock timing): the direct method
// from a start a few mm off O recovers the emulated twin's actual offsets, and
// the drives are off afterwards. Kept short (three circles, about 25 s).
#include <cstdio>

#include <gtest/gtest.h>

#include "hw/backends/drive_emulator.hpp"
#include "hw/procedures/zero_offset_search.hpp"
#include "../zero_test_util.hpp"

namespace gpm::hw {
namespace {

namespace fs = std::filesystem;

TEST(ZeroOffsetSearchModbus, DirectMethodThroughTheEmulatorFindsTheOffsets) {
  const test::TempDir dir("zero_modbus");
  const fs::path twin_hw = test::write_twin_hardware(dir, test::kActualOffsets, 17, 0.0);
  std::string map_text = test::read_text(test::kSrc + "/hw/examples/register_map_emulator.yaml");
  test::write_text(dir / "map.yaml", map_text);
  const RegisterMap map0 = load_register_map((dir / "map.yaml").string());
  ManualClock clock;  // moves only when the client waits for its next cycle
  EmulatorOptions eo;
  eo.clock = &clock;
  DriveEmulator emu(map0, twin_config_from_scenario((dir / "scenario.yaml").string(), 0.004), eo);
  const int port = emu.start();
  map_text.replace(map_text.find("port: 1502"), 10, "port: " + std::to_string(port));
  test::write_text(dir / "map.yaml", map_text);
  test::write_text(dir / "modbus.yaml",
                   "backend: modbus\nrate_hz: 250\ncontroller: " + test::kSrc +
                       "/models/gpm2002.yaml\nmodbus: {register_map: map.yaml}\n" + test::kSafetyYaml);
  const HardwareConfig cfg = load_hardware_config((dir / "modbus.yaml").string());
  auto hw = make_hardware(cfg, clock);
  ZeroSearchOptions o = test::fast_options({219.5, 252.5});
  o.method = ZeroMethod::kDirect;
  o.circle_radius_mm = 30.0;
  o.direct_iterations = 3;
  o.circle_speed_mm_s = 50.0;
  // Stop and average at each point of the circle: readings over the network
  // lag the commands by a time that varies with the machine's load, which a
  // moving circle turns into an offset error (up to 1.2e-3 rad measured).
  o.circle_dwell_s = 0.1;
  const ZeroSearchResult r = run_zero_offset_search(*hw, o);
  std::printf("modbus direct: ok %d offsets %.6f %.6f %.6f err %.2e circles %d motions %d wall %.1f s\n",
              r.ok, r.offsets[0], r.offsets[1], r.offsets[2],
              (r.offsets - test::kActualOffsets).cwiseAbs().maxCoeff(), r.circles, r.motions, r.wall_time_s);
  ASSERT_TRUE(r.ok) << r.error;
  // The start's step-2 offsets were wrong by > 5 mrad; three circles get within 1 mrad.
  EXPECT_GT((r.initial_offsets - test::kActualOffsets).cwiseAbs().maxCoeff(), 5e-3);
  EXPECT_LT((r.offsets - test::kActualOffsets).cwiseAbs().maxCoeff(), 1e-3);
  EXPECT_EQ(hw->state(), LifecycleState::kFinalized);
  emu.tick_now();  // the client's disable is in the control words: off at the next tick
  EXPECT_EQ(emu.power_on(), (std::array<bool, 3>{false, false, false}));
}

}  // namespace
}  // namespace gpm::hw
