// Helpers of the section-2 tests: a twin hardware file whose actual robot
// differs from the controller only in the zero offsets (paper section 2
// assumes link lengths and bases known), and fast procedure settings.
#pragma once

#include <filesystem>
#include <string>

#include <Eigen/Core>
#include <fmt/format.h>

#include "hw/hardware_config.hpp"
#include "hw/procedures/zero_offset_search.hpp"
#include "../hw_test_util.hpp"

namespace gpm::hw::test {

inline const std::string kSrc = GPM_SOURCE_DIR;

// The twin's actual offsets in these tests (rad).
inline const Eigen::Vector3d kActualOffsets(0.012, -0.008, 0.006);

// Writes DIR/scenario.yaml (actual = nominal + offsets, encoder bits and
// noise) and DIR/twin.yaml (hardware file with the example limits, workspace
// radius as given); returns the hardware file's path.
inline std::filesystem::path write_twin_hardware(const std::filesystem::path& dir,
                                                 const Eigen::Vector3d& offsets, int bits,
                                                 double noise_rad, double workspace_radius = 90,
                                                 int rate_hz = 250) {
  write_text(dir / "scenario.yaml",
             fmt::format("name: zero_test\nseed: 5\nrobot: {}/models/gpm2002.yaml\n"
                         "actual:\n  geometry: {{dth1: {}, dth2: {}, dth3: {}}}\n"
                         "servo: {{rate_hz: 2000}}\nencoder: {{bits: {}, noise_rad: {}}}\n"
                         "sampling: {{pattern: circle, centre: [216.5, 250], radius: 10, count: 4}}\n",
                         kSrc, offsets[0], offsets[1], offsets[2], bits, noise_rad));
  std::string safety = kSafetyYaml;
  safety.replace(safety.find("workspace_radius: 90"), 20,
                 fmt::format("workspace_radius: {}", workspace_radius));
  write_text(dir / "twin.yaml",
             fmt::format("backend: twin\nrate_hz: {}\ncontroller: {}/models/gpm2002.yaml\n"
                         "twin: {{scenario: scenario.yaml}}\n{}",
                         rate_hz, kSrc, safety));
  return dir / "twin.yaml";
}

// Short circles and few points: a run of the grid takes seconds on the twin.
inline ZeroSearchOptions fast_options(const Eigen::Vector2d& start) {
  ZeroSearchOptions o;
  o.circle_radius_mm = 30.0;
  o.circle_points = 24;
  o.circle_speed_mm_s = 100.0;
  o.move_speed_mm_s = 50.0;
  o.jog_to_start = true;
  o.start = start;
  return o;
}

// Runs the procedure on a fresh twin from a hardware file.
inline ZeroSearchResult run_on_twin(const std::filesystem::path& hw_file, const ZeroSearchOptions& o) {
  const HardwareConfig cfg = load_hardware_config(hw_file.string());
  auto hw = make_hardware(cfg);
  return run_zero_offset_search(*hw, o);
}

}  // namespace gpm::hw::test
