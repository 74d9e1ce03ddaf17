// Tests of hw/hardware_config.cpp: the examples load; a config without its
// safety limits is refused; bad values name the key.
#include <gtest/gtest.h>

#include "hw/hardware_config.hpp"
#include "hw_test_util.hpp"
#include "models/errors.hpp"

namespace gpm::hw {
namespace {

const std::string kSrc = GPM_SOURCE_DIR;

std::string error_of(const std::string& path) {
  try {
    load_hardware_config(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(HardwareConfig, ExamplesLoad) {
  const HardwareConfig t = load_hardware_config(kSrc + "/hw/examples/twin.yaml");
  EXPECT_EQ(t.backend, "twin");
  ASSERT_TRUE(t.twin.has_value());
  EXPECT_NE(t.twin->actual.geometry, t.controller.geometry);  // perturbed actual robot
  const HardwareConfig m = load_hardware_config(kSrc + "/hw/examples/modbus_emulator.yaml");
  EXPECT_EQ(m.backend, "modbus");
  EXPECT_EQ(m.register_map->port, 1502);
  EXPECT_EQ(make_hardware(m)->describe(), "supervised modbus-tcp 127.0.0.1:1502");
  EXPECT_EQ(t.dither_mm, 0.25);
  EXPECT_EQ(m.dither_mm, 0.25);
}

TEST(HardwareConfig, DitherOutsideZeroToFiveMmIsRefused) {
  const test::TempDir dir("cfg4");
  std::string text = test::read_text(kSrc + "/hw/examples/twin.yaml");
  for (const char* mm : {"-0.1", "5.5", "nan"}) {
    std::string t = text;
    t.replace(t.find("dither_mm: 0.25"), 15, std::string("dither_mm: ") + mm);
    test::write_text(dir / "hw.yaml", t);
    const std::string e = error_of((dir / "hw.yaml").string());
    EXPECT_NE(e.find("dither_mm"), std::string::npos) << mm << ": " << e;
  }
}

TEST(HardwareConfig, MissingSafetyIsRefused) {
  const test::TempDir dir("cfg");
  std::string text = test::read_text(kSrc + "/hw/examples/modbus_emulator.yaml");
  text = text.substr(0, text.find("safety:"));
  text.replace(text.find("register_map_emulator.yaml"), 26, kSrc + "/hw/examples/register_map_emulator.yaml");
  text.replace(text.find("../../models"), 12, kSrc + "/models");
  test::write_text(dir / "hw.yaml", text);
  EXPECT_NE(error_of((dir / "hw.yaml").string()).find("missing section 'safety'"), std::string::npos)
      << error_of((dir / "hw.yaml").string());
}

TEST(HardwareConfig, BadBackendNamesValidOnes) {
  const test::TempDir dir("cfg2");
  test::write_text(dir / "hw.yaml", "backend: ethercat\n");
  EXPECT_NE(error_of((dir / "hw.yaml").string()).find("not a backend (valid: twin, modbus)"),
            std::string::npos);
}

TEST(HardwareConfig, RateOutsideTenTo8000HzIsRefused) {
  const test::TempDir dir("cfg3");
  std::string text = test::read_text(kSrc + "/hw/examples/twin.yaml");
  for (const char* rate : {"0.001", "5", "8001"}) {
    std::string t = text;
    t.replace(t.find("rate_hz: 250"), 12, std::string("rate_hz: ") + rate);
    test::write_text(dir / "hw.yaml", t);
    const std::string e = error_of((dir / "hw.yaml").string());
    EXPECT_NE(e.find("outside [10, 8000] Hz"), std::string::npos) << rate << ": " << e;
  }
}

}  // namespace
}  // namespace gpm::hw
