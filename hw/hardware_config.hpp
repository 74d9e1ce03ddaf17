// Hardware file (YAML): which backend drives the robot (`twin`, `modbus` or
// `plugin`), the cycle rate, the controller model that computes IK (a robot
// file, optionally with the geometry of a calibration result), per-joint
// modes and the safety limits (all required). Switching backend is a config
// change only.
//
//   backend: twin | modbus | plugin
//   rate_hz: 250
//   controller: ../models/gpm2002.yaml
//   calibration: result.yaml          # optional
//   joint_modes: [position, position, position]   # optional
//   dither_mm: 0.25                   # optional: sampling's dither figure (0: hold still)
//   twin: {scenario: ../scenarios/simulate_disc.yaml}   # backend twin
//   modbus: {register_map: drives.yaml, timing: real_time}   # backend modbus; timing (optional):
//                                     # real_time (drives on their own clock, the default) or stepped
//                                     # (the drives advance one period per cycle: gpm-drive-emulator --stepped)
//   plugin: {library: libmycard.so, config: card.yaml}  # backend plugin: a shared library of
//                                     # the C ABI hw/plugin/gpm_backend_plugin.h; config (optional)
//                                     # a file the plugin reads or a map handed to it as YAML text
//   safety: {...}                                       # hw/safety_limits.hpp
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "hw/hardware_types.hpp"
#include "hw/backends/drive_backend.hpp"
#include "hw/backends/plugin_backend.hpp"
#include "hw/backends/register_map.hpp"
#include "hw/safety_limits.hpp"
#include "hw/safety_supervisor.hpp"
#include "hw/backends/twin_backend.hpp"
#include "models/robot.hpp"

namespace gpm::hw {

struct HardwareConfig {
  std::string file;
  std::string backend;  // "twin", "modbus" or "plugin"
  double rate_hz = 250.0;
  Robot controller;
  std::array<JointMode, 3> modes{JointMode::kPosition, JointMode::kPosition, JointMode::kPosition};
  // Size (mm) of the figure each calibration sample is averaged along
  // (hw/procedures/sampling_session.hpp); unset: the session's default.
  std::optional<double> dither_mm;
  SafetyLimits safety;
  std::optional<TwinBackendConfig> twin;   // backend twin
  std::optional<RegisterMap> register_map; // backend modbus
  DriveTiming timing = DriveTiming::kRealTime;  // backend modbus: modbus.timing
  std::optional<PluginBackendConfig> plugin; // backend plugin
};

// Loads and validates a hardware file; relative paths are taken from its
// folder. Throws InputError (file, key path, what is wrong, what is valid);
// a missing or incomplete safety section is refused.
HardwareConfig load_hardware_config(const std::string& path);

// The twin backend settings of a scenario file: its actual robot, servo and
// encoder settings, and the encoder noise seed.
TwinBackendConfig twin_config_from_scenario(const std::string& scenario_path, double period_s);

// The configured backend behind a safety supervisor (not yet configured);
// clock is real time for all (tests inject one). A plugin is loaded and its
// versions checked here (InputError: hw/backends/plugin_backend.hpp).
std::unique_ptr<SafetySupervisor> make_hardware(const HardwareConfig& config, Clock& clock = steady_clock());

}  // namespace gpm::hw
