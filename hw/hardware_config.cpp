#include "hw/hardware_config.hpp"

#include <filesystem>

#include <fmt/format.h>

#include "hw/backends/drive_backend.hpp"
#include "hw/backends/modbus_transport.hpp"
#include "models/errors.hpp"
#include "models/rng.hpp"
#include "models/robot_yaml.hpp"
#include "models/yaml_util.hpp"
#include "sim/scenario.hpp"

namespace gpm::hw {
namespace {

std::string resolve(const std::string& base_dir, const std::string& p) {
  const std::filesystem::path path(p);
  return path.is_absolute() ? p : (std::filesystem::path(base_dir) / path).lexically_normal().string();
}

// p taken from base_dir as an absolute path (a plugin is handed paths that
// do not depend on the working folder, and dlopen never searches for it).
std::string resolve_absolute(const std::string& base_dir, const std::string& p) {
  return std::filesystem::absolute(resolve(base_dir, p)).lexically_normal().string();
}

// The map node as one line of YAML flow text ({key: value, ...}).
std::string flow_text(const YAML::Node& node) {
  YAML::Emitter e;
  e.SetMapFormat(YAML::Flow);
  e.SetSeqFormat(YAML::Flow);
  e << YAML::Clone(node);
  return e.c_str();
}

// The section plugin: {library, config} of root into c (paths from dir;
// the library and a config file must exist).
void parse_plugin_section(const YAML::Node& root, const std::string& path, const std::string& dir,
                          HardwareConfig& c) {
  const YAML::Node p = root["plugin"];
  if (!p) {
    throw InputError(path + ": missing key 'plugin' (backend plugin needs plugin: {library: FILE.so, config: FILE "
                            "or {...}})");
  }
  if (!p.IsMap()) throw InputError(yaml_where(path, p, "plugin") + "expected a map {library: FILE.so, config: ...}");
  yaml_check_keys(p, path, "plugin", {"library", "config"});
  if (!p["library"]) {
    throw InputError(yaml_where(path, p, "plugin") +
                     "missing key 'library' (a shared library built against hw/plugin/gpm_backend_plugin.h)");
  }
  PluginBackendConfig pc;
  pc.library = resolve_absolute(dir, yaml_string(p["library"], path, "plugin.library"));
  if (!std::filesystem::is_regular_file(pc.library)) {
    throw InputError(yaml_where(path, p["library"], "plugin.library") +
                     fmt::format("no file {} (a shared library built against hw/plugin/gpm_backend_plugin.h)",
                                 pc.library));
  }
  pc.base_dir = std::filesystem::absolute(dir.empty() ? "." : dir).lexically_normal().string();
  if (pc.base_dir.size() > 1 && pc.base_dir.back() == '/') pc.base_dir.pop_back();
  if (const YAML::Node k = p["config"]) {
    if (k.IsMap()) {
      pc.config_text = flow_text(k);
    } else if (k.IsScalar()) {
      pc.config_path = resolve_absolute(dir, yaml_string(k, path, "plugin.config"));
      if (!std::filesystem::is_regular_file(*pc.config_path)) {
        throw InputError(yaml_where(path, k, "plugin.config") + fmt::format("no file {}", *pc.config_path));
      }
      pc.base_dir = std::filesystem::path(*pc.config_path).parent_path().string();
    } else {
      throw InputError(yaml_where(path, k, "plugin.config") +
                       "expected a file name or a map (the plugin's own configuration)");
    }
  }
  pc.source = path;
  pc.period_s = 1.0 / c.rate_hz;
  c.plugin = std::move(pc);
}

// The key backend (twin, modbus or plugin) of root.
std::string parse_backend(const YAML::Node& root, const std::string& path) {
  if (!root["backend"]) throw InputError(path + ": missing key 'backend' (twin, modbus or plugin)");
  std::string backend = yaml_string(root["backend"], path, "backend");
  if (backend != "twin" && backend != "modbus" && backend != "plugin") {
    throw InputError(yaml_where(path, root["backend"], "backend") +
                     fmt::format("'{}' is not a backend (valid: twin, modbus, plugin)", backend));
  }
  return backend;
}

// Throws InputError at node (key path key) unless lo <= v <= hi; what: the explanation.
void check_within(double v, double lo, double hi, const YAML::Node& node, const std::string& path, const char* key,
                  const std::string& what) {
  if (!(v >= lo && v <= hi)) throw InputError(yaml_where(path, node, key) + what);
}

// The key dither_mm of node d: within [0, 5] mm.
double parse_dither(const YAML::Node& d, const std::string& path) {
  const double v = yaml_number(d, path, "dither_mm");
  check_within(v, 0.0, 5.0, d, path, "dither_mm",
               fmt::format("{} mm is outside [0, 5] mm (the figure each sample is averaged along; 0: hold still)", v));
  return v;
}

// The key rate_hz of node r: within [10, 8000] Hz (EtherCAT drives cycle at up to 8 kHz).
double parse_rate(const YAML::Node& r, const std::string& path) {
  const double rate_hz = yaml_positive(r, path, "rate_hz");
  check_within(rate_hz, 10.0, 8000.0, r, path, "rate_hz",
               fmt::format("{} Hz is outside [10, 8000] Hz (the read/write cycle of the drives; the examples use 250)",
                           rate_hz));
  return rate_hz;
}

// The controller model: the robot file of key controller (paths relative to
// dir), its geometry replaced by that of the file of key calibration when given.
Robot parse_controller(const YAML::Node& root, const std::string& path, const std::string& dir) {
  if (!root["controller"]) {
    throw InputError(path + ": missing key 'controller' (the robot file whose model computes IK, "
                            "e.g. models/gpm2002.yaml)");
  }
  Robot controller = load_robot(resolve(dir, yaml_string(root["controller"], path, "controller")));
  if (root["calibration"]) {
    const std::string cal = resolve(dir, yaml_string(root["calibration"], path, "calibration"));
    const YAML::Node r = load_yaml_file(cal);
    controller.geometry = geometry_from_yaml(r["geometry"], cal, "geometry");
    validate_robot(controller, cal);
  }
  return controller;
}

// The key joint_modes of node m into modes: three of position or
// torque_off, at least two in position mode.
void parse_joint_modes(const YAML::Node& m, const std::string& path, std::array<JointMode, 3>& modes) {
  if (!m.IsSequence() || m.size() != 3) {
    throw InputError(yaml_where(path, m, "joint_modes") +
                     "expected three modes, each position or torque_off");
  }
  for (size_t i = 0; i < 3; ++i) {
    const std::string kp = fmt::format("joint_modes[{}]", i);
    const std::string s = yaml_string(m[i], path, kp);
    if (s == "position") modes[i] = JointMode::kPosition;
    else if (s == "torque_off") modes[i] = JointMode::kTorqueOff;
    else throw InputError(yaml_where(path, m[i], kp) + fmt::format("'{}' is not position or torque_off", s));
  }
  int n = 0;
  for (JointMode x : modes) n += x == JointMode::kPosition;
  if (n < 2) {
    throw InputError(yaml_where(path, m, "joint_modes") +
                     "at least two joints must be in position mode (2 degrees of freedom)");
  }
}

// modbus.timing (node t) into c: real_time or stepped, the latter only with a
// latch that reports its time.
void parse_timing(const YAML::Node& t, const std::string& path, HardwareConfig& c) {
  const std::string v = yaml_string(t, path, "modbus.timing");
  if (v == "real_time") return;
  if (v != "stepped")
    throw InputError(yaml_where(path, t, "modbus.timing") +
                     fmt::format("'{}' is not a timing (valid: real_time: drives on their own clock; stepped: "
                                 "the drives advance one period per cycle, as gpm-drive-emulator --stepped)",
                                 v));
  const std::optional<LatchRegister>& l = c.register_map->latch;
  if (!l || l->time_address < 0)
    throw InputError(yaml_where(path, t, "modbus.timing") +
                     "stepped needs a register map whose latch reports its time (latch: {unit_id, register, "
                     "time}), by which each cycle checks that the drives advanced one period");
  c.timing = DriveTiming::kStepped;
}

// The backend's own section into c: twin {scenario}, modbus {register_map}
// (whose response_timeout must fit within safety.comms_timeout) or plugin
// {library, config}.
void parse_backend_section(const YAML::Node& root, const std::string& path, const std::string& dir,
                           HardwareConfig& c) {
  if (c.backend == "plugin") return parse_plugin_section(root, path, dir, c);
  if (c.backend == "twin") {
    const YAML::Node t = root["twin"];
    if (!t) throw InputError(path + ": missing key 'twin' (backend twin needs twin: {scenario: FILE})");
    yaml_check_keys(t, path, "twin", {"scenario"});
    if (!t["scenario"]) throw InputError(yaml_where(path, t, "twin") + "missing key 'scenario'");
    c.twin = twin_config_from_scenario(resolve(dir, yaml_string(t["scenario"], path, "twin.scenario")),
                                       1.0 / c.rate_hz);
    return;
  }
  const YAML::Node m = root["modbus"];
  if (!m) throw InputError(path + ": missing key 'modbus' (backend modbus needs modbus: {register_map: FILE})");
  yaml_check_keys(m, path, "modbus", {"register_map", "timing"});
  if (!m["register_map"]) throw InputError(yaml_where(path, m, "modbus") + "missing key 'register_map'");
  c.register_map = load_register_map(resolve(dir, yaml_string(m["register_map"], path, "modbus.register_map")));
  if (const YAML::Node t = m["timing"]) parse_timing(t, path, c);
  if (c.register_map->response_timeout_s > c.safety.comms_timeout_s) {
    throw InputError(yaml_where(path, root["safety"], "safety.comms_timeout") +
                     fmt::format("{} s is shorter than the register map's response_timeout {} s",
                                 c.safety.comms_timeout_s, c.register_map->response_timeout_s));
  }
}

}  // namespace

TwinBackendConfig twin_config_from_scenario(const std::string& scenario_path, double period_s) {
  const sim::Scenario sc = sim::load_scenario(scenario_path);
  TwinBackendConfig t;
  t.actual = sim::make_actual(sc);
  t.twin = sc.twin;
  t.seed = derive_seed(sc.seed, Stream::kTwinNoise);
  t.period_s = period_s;
  return t;
}

HardwareConfig load_hardware_config(const std::string& path) {
  const YAML::Node root = load_yaml_file(path);
  const std::string dir = std::filesystem::path(path).parent_path().string();
  if (!root.IsMap()) throw InputError(path + ": expected a map with keys backend, rate_hz, controller, safety, ...");
  yaml_check_keys(root, path, "",
                  {"backend", "rate_hz", "controller", "calibration", "joint_modes", "dither_mm", "twin",
                   "modbus", "plugin", "safety"});
  HardwareConfig c;
  c.file = path;
  c.backend = parse_backend(root, path);
  if (const YAML::Node d = root["dither_mm"]) c.dither_mm = parse_dither(d, path);
  if (root["rate_hz"]) c.rate_hz = parse_rate(root["rate_hz"], path);
  c.controller = parse_controller(root, path, dir);
  if (const YAML::Node m = root["joint_modes"]) parse_joint_modes(m, path, c.modes);
  c.safety = safety_limits_from_yaml(root["safety"], path, "safety");
  parse_backend_section(root, path, dir, c);
  return c;
}

std::unique_ptr<SafetySupervisor> make_hardware(const HardwareConfig& c, Clock& clock) {
  const double period = 1.0 / c.rate_hz;
  std::unique_ptr<RobotHardware> backend;
  if (c.backend == "twin") {
    backend = std::make_unique<TwinBackend>(*c.twin);
  } else if (c.backend == "plugin") {
    backend = std::make_unique<PluginBackend>(*c.plugin);
  } else {
    const RegisterMap& m = *c.register_map;
    backend = std::make_unique<DriveBackend>(
        m, std::make_unique<ModbusTransport>(m.host, m.port, m.response_timeout_s, clock), period, clock,
        c.timing);
  }
  return std::make_unique<SafetySupervisor>(std::move(backend), c.controller, c.safety, clock);
}

}  // namespace gpm::hw
