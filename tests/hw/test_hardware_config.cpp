// Tests of hw/hardware_config.cpp: the examples load; a config without its
// safety limits is refused; bad values name the key; the plugin section's
// paths are taken from the hardware file's folder and its map handed on as
// YAML text.
#include <gtest/gtest.h>

#include <filesystem>

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

// modbus.timing: real_time (the default) or stepped; stepped needs a latch
// that reports its time; anything else is refused naming the key.
TEST(HardwareConfig, ModbusTimingIsRealTimeOrSteppedWithALatchTime) {
  const test::TempDir dir("cfg5");
  std::string text = test::read_text(kSrc + "/hw/examples/modbus_emulator.yaml");
  text.replace(text.find("register_map: register_map_emulator.yaml"), 40, "register_map: " + (dir / "map.yaml").string());
  text.replace(text.find("../../models"), 12, kSrc + "/models");
  std::string map = test::read_text(kSrc + "/hw/examples/register_map_emulator.yaml");
  test::write_text(dir / "map.yaml", map);
  auto with_timing = [&](const std::string& timing) {
    std::string t = text;
    t.replace(t.find("\n", t.find("  register_map:")), 1, "\n  timing: " + timing + "\n");
    test::write_text(dir / "hw.yaml", t);
    return (dir / "hw.yaml").string();
  };
  test::write_text(dir / "hw.yaml", text);
  EXPECT_EQ(load_hardware_config((dir / "hw.yaml").string()).timing, DriveTiming::kRealTime);
  EXPECT_FALSE(make_hardware(load_hardware_config((dir / "hw.yaml").string()))->simulated_time());
  EXPECT_EQ(load_hardware_config(with_timing("real_time")).timing, DriveTiming::kRealTime);
  const HardwareConfig stepped = load_hardware_config(with_timing("stepped"));
  EXPECT_EQ(stepped.timing, DriveTiming::kStepped);
  EXPECT_TRUE(make_hardware(stepped)->simulated_time());  // the procedure's time is its count of cycles
  std::string e = error_of(with_timing("lockstep"));
  EXPECT_NE(e.find("modbus.timing: 'lockstep' is not a timing (valid: real_time"), std::string::npos) << e;
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  // A latch without its time cannot be checked cycle by cycle.
  map.replace(map.find(", time: 32"), 10, "");
  test::write_text(dir / "map.yaml", map);
  e = error_of(with_timing("stepped"));
  EXPECT_NE(e.find("modbus.timing"), std::string::npos) << e;
  EXPECT_NE(e.find("latch reports its time"), std::string::npos) << e;
  EXPECT_EQ(load_hardware_config(with_timing("real_time")).timing, DriveTiming::kRealTime);
}

TEST(HardwareConfig, BadBackendNamesValidOnes) {
  const test::TempDir dir("cfg2");
  test::write_text(dir / "hw.yaml", "backend: ethercat\n");
  EXPECT_NE(error_of((dir / "hw.yaml").string()).find("not a backend (valid: twin, modbus, plugin)"),
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

// A hardware file of backend plugin in dir with the given plugin section.
std::string plugin_yaml(const std::string& section) {
  return "backend: plugin\nrate_hz: 500\ncontroller: " + kSrc + "/models/gpm2002.yaml\n" + section +
         test::kSafetyYaml;
}

TEST(HardwareConfig, PluginSectionPathsAreTakenFromTheHardwareFile) {
  const test::TempDir dir("cfg_plugin");
  std::filesystem::create_directories(dir / "lib");
  std::filesystem::create_directories(dir / "card");
  test::write_text(dir / "lib/libcard.so", "");
  test::write_text(dir / "card/card.yaml", "axes: 3\n");
  test::write_text(dir / "hw.yaml", plugin_yaml("plugin: {library: lib/libcard.so, config: card/card.yaml}\n"));
  const HardwareConfig c = load_hardware_config((dir / "hw.yaml").string());
  ASSERT_TRUE(c.plugin.has_value());
  const std::filesystem::path root = std::filesystem::absolute(dir.path());
  EXPECT_EQ(c.plugin->library, (root / "lib/libcard.so").string());
  EXPECT_EQ(c.plugin->config_path, (root / "card/card.yaml").string());
  EXPECT_EQ(c.plugin->base_dir, (root / "card").string());  // the config file's own folder
  EXPECT_FALSE(c.plugin->config_text.has_value());
  EXPECT_DOUBLE_EQ(c.plugin->period_s, 1.0 / 500);
  // A map is handed on as one line of YAML; its paths are the hardware file's.
  test::write_text(dir / "hw.yaml",
                   plugin_yaml("plugin:\n  library: lib/libcard.so\n  config:\n    scenario: s.yaml\n"
                               "    gains: [1, 2.5]\n"));
  const HardwareConfig m = load_hardware_config((dir / "hw.yaml").string());
  EXPECT_EQ(m.plugin->config_text, "{scenario: s.yaml, gains: [1, 2.5]}");
  EXPECT_EQ(m.plugin->base_dir, root.lexically_normal().string());
  EXPECT_FALSE(m.plugin->config_path.has_value());
}

TEST(HardwareConfig, BadPluginSectionIsOneLineNamingTheKey) {
  const test::TempDir dir("cfg_plugin_bad");
  test::write_text(dir / "libcard.so", "");
  const std::pair<std::string, std::string> cases[] = {
      {"", "missing key 'plugin'"},
      {"plugin: libcard.so\n", "plugin: expected a map"},
      {"plugin: {config: c.yaml}\n", "missing key 'library'"},
      {"plugin: {library: libcard.so, libary: x}\n", "libary"},
      {"plugin: {library: libnone.so}\n", "plugin.library: no file"},
      {"plugin: {library: libcard.so, config: none.yaml}\n", "plugin.config: no file"},
      {"plugin: {library: libcard.so, config: [1, 2]}\n", "plugin.config: expected a file name or a map"},
  };
  for (const auto& [section, words] : cases) {
    test::write_text(dir / "hw.yaml", plugin_yaml(section));
    const std::string e = error_of((dir / "hw.yaml").string());
    EXPECT_NE(e.find(words), std::string::npos) << section << ": " << e;
    EXPECT_NE(e.find("hw.yaml"), std::string::npos) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  }
}

}  // namespace
}  // namespace gpm::hw
