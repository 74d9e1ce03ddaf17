#include "hw/backends/register_map.hpp"

#include <arpa/inet.h>

#include <algorithm>
#include <cmath>
#include <vector>
#include <numbers>

#include <fmt/format.h>

#include "hw/hw_errors.hpp"
#include "models/errors.hpp"
#include "models/kinematics.hpp"
#include "models/yaml_util.hpp"

namespace gpm::hw {
namespace {

int reg(const YAML::Node& n, const std::string& file, const std::string& kp, bool optional) {
  if (!n) {
    if (optional) return -1;
    throw InputError(fmt::format("{}: {}: missing key (a holding-register address 0..65534)", file, kp));
  }
  return static_cast<int>(yaml_integer(n, file, kp, 0, 65534));
}

RegisterBit bit(const YAML::Node& n, const std::string& file, const std::string& kp) {
  if (!n) {
    throw InputError(fmt::format("{}: {}: missing key (expected {{register: ADDRESS, bit: 0..15}})",
                                 file, kp));
  }
  yaml_check_keys(n, file, kp, {"register", "bit"});
  RegisterBit b;
  b.address = reg(n["register"], file, kp + ".register", false);
  if (!n["bit"]) throw InputError(yaml_where(file, n, kp) + "missing key 'bit' (0..15)");
  b.bit = static_cast<int>(yaml_integer(n["bit"], file, kp + ".bit", 0, 15));
  return b;
}

AxisRegisters axis_from_yaml(const YAML::Node& n, const std::string& file, const std::string& kp) {
  yaml_check_keys(n, file, kp,
                  {"unit_id", "position_command", "actual_position", "actual_velocity",
                   "actual_torque", "torque_unit", "status_word", "control_word", "fault_code",
                   "enable", "enabled", "fault", "counts_per_rev", "sign", "offset", "latched_position",
                   "latch_id"});
  AxisRegisters a;
  if (!n["unit_id"]) throw InputError(yaml_where(file, n, kp) + "missing key 'unit_id' (1..247)");
  a.unit_id = static_cast<int>(yaml_integer(n["unit_id"], file, kp + ".unit_id", 0, 247));
  if (a.unit_id == 0) {
    throw InputError(yaml_where(file, n["unit_id"], kp + ".unit_id") +
                     "0 is the Modbus broadcast address (every drive obeys, none replies): give "
                     "the drive's own unit id, 1..247");
  }
  a.position_command = reg(n["position_command"], file, kp + ".position_command", false);
  a.actual_position = reg(n["actual_position"], file, kp + ".actual_position", false);
  a.actual_velocity = reg(n["actual_velocity"], file, kp + ".actual_velocity", true);
  a.actual_torque = reg(n["actual_torque"], file, kp + ".actual_torque", true);
  if (n["torque_unit"]) a.torque_unit_nm = yaml_positive(n["torque_unit"], file, kp + ".torque_unit");
  a.status_word = reg(n["status_word"], file, kp + ".status_word", false);
  a.control_word = reg(n["control_word"], file, kp + ".control_word", false);
  a.fault_code = reg(n["fault_code"], file, kp + ".fault_code", true);
  a.latched_position = reg(n["latched_position"], file, kp + ".latched_position", true);
  a.latch_id = reg(n["latch_id"], file, kp + ".latch_id", true);
  a.enable = bit(n["enable"], file, kp + ".enable");
  a.enabled = bit(n["enabled"], file, kp + ".enabled");
  a.fault = bit(n["fault"], file, kp + ".fault");
  if (!n["counts_per_rev"])
    throw InputError(yaml_where(file, n, kp) + "missing key 'counts_per_rev' (e.g. 131072 for 17 bits)");
  a.counts_per_rev = yaml_integer(n["counts_per_rev"], file, kp + ".counts_per_rev", 2, 1LL << 31);
  if (!n["sign"]) throw InputError(yaml_where(file, n, kp) + "missing key 'sign' (1 or -1)");
  const long long s = yaml_integer(n["sign"], file, kp + ".sign", -1, 1);
  if (s == 0) throw InputError(yaml_where(file, n["sign"], kp + ".sign") + "must be 1 or -1, got 0");
  a.sign = static_cast<int>(s);
  if (!n["offset"]) throw InputError(yaml_where(file, n, kp) + "missing key 'offset' (counts at theta_m = 0)");
  a.offset_counts = yaml_integer(n["offset"], file, kp + ".offset", -(1LL << 31), (1LL << 31) - 1);
  // Written registers must not overlap anything read back.
  const int pc = a.position_command;
  std::vector<int> read_back{a.actual_position, a.actual_position + 1, a.status_word, a.control_word};
  if (a.latched_position >= 0) read_back.insert(read_back.end(), {a.latched_position, a.latched_position + 1});
  if (a.latch_id >= 0) read_back.push_back(a.latch_id);
  for (int r : read_back) {
    if (r == pc || r == pc + 1) {
      throw InputError(yaml_where(file, n["position_command"], kp + ".position_command") +
                       fmt::format("registers {}..{} overlap register {} (give each value its own "
                                   "registers)",
                                   pc, pc + 1, r));
    }
  }
  if (a.control_word == a.status_word) {
    throw InputError(yaml_where(file, n["control_word"], kp + ".control_word") +
                     "must differ from status_word");
  }
  return a;
}

// Throws InputError unless host is the IPv4 address of one machine (node: its YAML node).
void check_host(const std::string& host_text, const YAML::Node& node, const std::string& file) {
  in_addr addr{};
  if (inet_pton(AF_INET, host_text.c_str(), &addr) != 1) {
    throw InputError(yaml_where(file, node, "connection.host") +
                     fmt::format("'{}' is not an IPv4 address (give the drives' address as "
                                 "digits, e.g. 192.168.10.11; names are not resolved)",
                                 host_text));
  }
  const std::uint32_t host = ntohl(addr.s_addr);
  if (host == 0 || host == 0xffffffffu || (host >> 28) == 0xe) {
    throw InputError(yaml_where(file, node, "connection.host") +
                     fmt::format("'{}' is not one machine (0.0.0.0, broadcast or multicast): give "
                                 "the drives' own address, e.g. 192.168.10.11",
                                 host_text));
  }
}

// The section connection (host, port, response_timeout) of root into m.
void parse_connection(const YAML::Node& root, const std::string& file, RegisterMap& m) {
  const YAML::Node c = root["connection"];
  if (!c) throw InputError(file + ": missing key 'connection' (host, port, response_timeout)");
  yaml_check_keys(c, file, "connection", {"host", "port", "response_timeout"});
  if (!c["host"]) throw InputError(yaml_where(file, c, "connection") + "missing key 'host' (an IPv4 address)");
  m.host = yaml_string(c["host"], file, "connection.host");
  check_host(m.host, c["host"], file);
  if (!c["port"]) throw InputError(yaml_where(file, c, "connection") + "missing key 'port' (1..65535)");
  m.port = static_cast<int>(yaml_integer(c["port"], file, "connection.port", 1, 65535));
  if (c["response_timeout"]) {
    m.response_timeout_s = yaml_positive(c["response_timeout"], file, "connection.response_timeout");
    if (m.response_timeout_s > 10.0) {
      throw InputError(yaml_where(file, c["response_timeout"], "connection.response_timeout") +
                       "must be at most 10 s");
    }
  }
}

// The key word_order (high_first or low_first) of node w.
WordOrder parse_word_order(const YAML::Node& w_node, const std::string& file) {
  const std::string w = yaml_string(w_node, file, "word_order");
  if (w == "high_first") return WordOrder::kHighFirst;
  if (w == "low_first") return WordOrder::kLowFirst;
  throw InputError(yaml_where(file, w_node, "word_order") + fmt::format("'{}' is not high_first or low_first", w));
}

// The section latch {unit_id, register, time} of node l.
LatchRegister parse_latch(const YAML::Node& l, const std::string& file) {
  yaml_check_keys(l, file, "latch", {"unit_id", "register", "time"});
  if (!l["unit_id"] || !l["register"])
    throw InputError(yaml_where(file, l, "latch") +
                     "expected {unit_id: 1..247, register: ADDRESS, time: ADDRESS (optional)}");
  LatchRegister latch;
  latch.unit_id = static_cast<int>(yaml_integer(l["unit_id"], file, "latch.unit_id", 1, 247));
  latch.address = reg(l["register"], file, "latch.register", false);
  latch.time_address = reg(l["time"], file, "latch.time", true);
  if (latch.time_address >= 0 && latch.time_address <= latch.address && latch.address <= latch.time_address + 1)
    throw InputError(yaml_where(file, l["time"], "latch.time") +
                     fmt::format("registers {} and {} (the latch time, two registers) overlap latch.register {}",
                                 latch.time_address, latch.time_address + 1, latch.address));
  return latch;
}

// Every register axis a uses on its unit (32-bit values take two).
std::vector<int> used_registers(const AxisRegisters& a) {
  std::vector<int> r{a.position_command, a.position_command + 1, a.actual_position,
                     a.actual_position + 1, a.status_word, a.control_word};
  if (a.actual_velocity >= 0) r.insert(r.end(), {a.actual_velocity, a.actual_velocity + 1});
  if (a.actual_torque >= 0) r.push_back(a.actual_torque);
  if (a.fault_code >= 0) r.push_back(a.fault_code);
  if (a.latched_position >= 0) r.insert(r.end(), {a.latched_position, a.latched_position + 1, a.latch_id});
  return r;
}

// Throws InputError unless the latch is given with latched_position and
// latch_id on every axis (or none of the three), and its register is no axis's on its unit.
void check_latch(const RegisterMap& m, const YAML::Node& root, const std::string& file) {
  const YAML::Node axes = root["axes"];
  for (size_t i = 0; i < 3; ++i) {
    const AxisRegisters& a = m.axes[i];
    const bool has = a.latched_position >= 0 && a.latch_id >= 0;
    if (has != m.latch.has_value() || (a.latched_position >= 0) != (a.latch_id >= 0)) {
      throw InputError(yaml_where(file, axes[i], fmt::format("axes[{}]", i)) +
                       "a latch needs the top-level key latch: {unit_id, register} and latched_position "
                       "and latch_id on every axis (or none of the three)");
    }
    if (!m.latch || m.latch->unit_id != a.unit_id) continue;
    const std::vector<int> r = used_registers(a);
    if (std::find(r.begin(), r.end(), m.latch->address) != r.end())
      throw InputError(yaml_where(file, root["latch"]["register"], "latch.register") +
                       fmt::format("register {} of unit {} is already used by axes[{}]", m.latch->address,
                                   a.unit_id, i));
    const int t = m.latch->time_address;
    if (t >= 0 && (std::find(r.begin(), r.end(), t) != r.end() || std::find(r.begin(), r.end(), t + 1) != r.end()))
      throw InputError(yaml_where(file, root["latch"]["time"], "latch.time") +
                       fmt::format("registers {} and {} of unit {} (the latch time) are already used by axes[{}]",
                                   t, t + 1, a.unit_id, i));
  }
}

// Axes on one unit id (one drive serving several axes) must use distinct
// registers: throws InputError for the first register two of them share.
void check_shared_units(const RegisterMap& m, const YAML::Node& axes, const std::string& file) {
  for (size_t i = 0; i < 3; ++i) {
    for (size_t j = 0; j < i; ++j) {
      if (m.axes[i].unit_id != m.axes[j].unit_id) continue;
      for (int ri : used_registers(m.axes[i])) {
        for (int rj : used_registers(m.axes[j])) {
          if (ri != rj) continue;
          throw InputError(yaml_where(file, axes[i], fmt::format("axes[{}]", i)) +
                           fmt::format("shares unit_id {} and register {} with axes[{}]: two "
                                       "axes would command and read the same drive values",
                                       m.axes[i].unit_id, ri, j));
        }
      }
    }
  }
}

}  // namespace

RegisterMap parse_register_map(const std::string& text, const std::string& file) {
  const YAML::Node root = load_yaml_string(text, file);
  if (!root.IsMap()) throw InputError(file + ": expected a map with keys connection, word_order, axes");
  yaml_check_keys(root, file, "", {"connection", "word_order", "axes", "latch"});
  RegisterMap m;
  parse_connection(root, file, m);
  if (root["word_order"]) m.word_order = parse_word_order(root["word_order"], file);
  const YAML::Node axes = root["axes"];
  if (!axes || !axes.IsSequence() || axes.size() != 3) {
    throw InputError(yaml_where(file, axes ? axes : root, "axes") +
                     "expected a list of three axes (joints 1, 2, 3)");
  }
  for (size_t i = 0; i < 3; ++i) m.axes[i] = axis_from_yaml(axes[i], file, fmt::format("axes[{}]", i));
  if (const YAML::Node l = root["latch"]) m.latch = parse_latch(l, file);
  check_latch(m, root, file);
  check_shared_units(m, axes, file);
  return m;
}

RegisterMap load_register_map(const std::string& path) {
  const YAML::Node probe = load_yaml_file(path);  // names a missing file clearly
  return parse_register_map(YAML::Dump(probe), path);
}

std::string register_map_to_yaml(const RegisterMap& m) {
  std::string out;
  out += fmt::format("connection:\n  host: {}\n  port: {}\n  response_timeout: {}\n", m.host,
                     m.port, format_exact(m.response_timeout_s));
  out += fmt::format("word_order: {}\n", m.word_order == WordOrder::kHighFirst ? "high_first"
                                                                              : "low_first");
  out += "axes:\n";
  auto b = [](const RegisterBit& x) { return fmt::format("{{register: {}, bit: {}}}", x.address, x.bit); };
  for (const AxisRegisters& a : m.axes) {
    out += fmt::format("  - unit_id: {}\n", a.unit_id);
    out += fmt::format("    position_command: {}\n    actual_position: {}\n", a.position_command,
                       a.actual_position);
    if (a.actual_velocity >= 0) out += fmt::format("    actual_velocity: {}\n", a.actual_velocity);
    if (a.actual_torque >= 0) out += fmt::format("    actual_torque: {}\n", a.actual_torque);
    out += fmt::format("    torque_unit: {}\n", format_exact(a.torque_unit_nm));
    out += fmt::format("    status_word: {}\n    control_word: {}\n", a.status_word, a.control_word);
    if (a.fault_code >= 0) out += fmt::format("    fault_code: {}\n", a.fault_code);
    out += fmt::format("    enable: {}\n    enabled: {}\n    fault: {}\n", b(a.enable),
                       b(a.enabled), b(a.fault));
    out += fmt::format("    counts_per_rev: {}\n    sign: {}\n    offset: {}\n", a.counts_per_rev,
                       a.sign, a.offset_counts);
    if (a.latched_position >= 0)
      out += fmt::format("    latched_position: {}\n    latch_id: {}\n", a.latched_position, a.latch_id);
  }
  if (m.latch) {
    out += fmt::format("latch: {{unit_id: {}, register: {}", m.latch->unit_id, m.latch->address);
    if (m.latch->time_address >= 0) out += fmt::format(", time: {}", m.latch->time_address);
    out += "}\n";
  }
  return out;
}

double counts_to_theta(const AxisRegisters& a, std::int64_t counts) {
  const double rev = static_cast<double>(a.sign * (counts - a.offset_counts)) /
                     static_cast<double>(a.counts_per_rev);
  return wrap_2pi(rev * 2.0 * std::numbers::pi);
}

std::int32_t theta_to_counts(const AxisRegisters& a, double theta_m) {
  const double c = static_cast<double>(a.offset_counts) +
                   a.sign * std::round(theta_m / (2.0 * std::numbers::pi) *
                                       static_cast<double>(a.counts_per_rev));
  if (!(c >= -2147483648.0 && c <= 2147483647.0)) {
    throw HardwareError(fmt::format("position command {} rad does not fit in 32-bit counts", theta_m));
  }
  return static_cast<std::int32_t>(c);
}

std::array<std::uint16_t, 2> split32(std::int32_t v, WordOrder order) {
  const auto u = static_cast<std::uint32_t>(v);
  const auto hi = static_cast<std::uint16_t>(u >> 16), lo = static_cast<std::uint16_t>(u & 0xffffu);
  return order == WordOrder::kHighFirst ? std::array<std::uint16_t, 2>{hi, lo}
                                        : std::array<std::uint16_t, 2>{lo, hi};
}

std::int32_t join32(const std::uint16_t* r, WordOrder order) {
  const std::uint32_t hi = order == WordOrder::kHighFirst ? r[0] : r[1];
  const std::uint32_t lo = order == WordOrder::kHighFirst ? r[1] : r[0];
  return static_cast<std::int32_t>((hi << 16) | lo);
}

}  // namespace gpm::hw
