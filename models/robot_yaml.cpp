#include "models/robot_yaml.hpp"

#include <cstdio>
#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <limits>
#include <cmath>

#include <fmt/format.h>

#include "models/data_sheet.hpp"
#include "models/errors.hpp"
#include "models/kinematics.hpp"
#include "models/output_file.hpp"
#include "models/yaml_util.hpp"

namespace gpm {
namespace {

std::string join(const std::string& a, const std::string& b) { return a.empty() ? b : a + "." + b; }

// A number that may also be .nan / .inf (a result's std and diagnostics may carry them).
double number_or_special(const YAML::Node& n, const std::string& file, const std::string& key) {
  if (n.IsScalar()) {
    const std::string& s = n.Scalar();
    if (s == ".nan" || s == ".NaN" || s == ".NAN") return std::numeric_limits<double>::quiet_NaN();
    if (s == ".inf" || s == ".Inf" || s == "+.inf") return std::numeric_limits<double>::infinity();
  }
  return yaml_number(n, file, key);
}

std::string number_text(double x) {
  if (std::isnan(x)) return ".nan";
  if (std::isinf(x)) return x > 0 ? ".inf" : "-.inf";
  return format_exact(x);
}

// Flow YAML text of a node (scalars quoted where YAML needs it).
std::string flow_text(const YAML::Node& n) {
  YAML::Emitter e;
  e.SetSeqFormat(YAML::Flow);
  e.SetMapFormat(YAML::Flow);
  e << n;
  return e.c_str();
}

}  // namespace

// Beyond these a 1-sigma says nothing of the robot (its links are 244 mm),
// and its square would overflow the monitor's filter.
double sigma_max(int param) { return is_offset(param) ? 1.0 : 100.0; }

double sigma_for_file(double sigma, int param) {
  return sigma >= 0.0 && sigma <= sigma_max(param) ? sigma : std::numeric_limits<double>::quiet_NaN();
}

double sigma_from_yaml(const YAML::Node& value, const std::string& file, const std::string& key, int param) {
  const bool angle = is_offset(param);
  const double max = sigma_max(param);
  const double v = number_or_special(value, file, key);
  if (std::isnan(v)) return v;
  if (!(v >= 0.0 && v <= max))
    throw InputError(yaml_where(file, value, key) +
                     fmt::format("a 1-sigma must be .nan (not determined) or from 0 to {} {}, got {}", max,
                                 angle ? "rad" : "mm", v));
  return v;
}

namespace {

// The `std`, `fixed` and `diagnostics` sections of a calibration result file
// (calib/result_yaml.hpp writes them), validated and kept.
CalibrationRecord calibration_from_yaml(const YAML::Node& root, const std::string& file,
                                        const std::string& keypath) {
  CalibrationRecord c;
  if (const YAML::Node fixed = root["fixed"]) {
    const std::string fp = join(keypath, "fixed");
    if (!fixed.IsSequence())
      throw InputError(yaml_where(file, fixed, fp) + "expected a list of parameter names, e.g. [xa1, ya1, xa2, ya2]");
    for (size_t k = 0; k < fixed.size(); ++k) {
      const std::string key = fmt::format("{}[{}]", fp, k);
      const std::string name = yaml_string(fixed[k], file, key);
      const auto i = param_index(name);
      if (!i) throw InputError(yaml_where(file, fixed[k], key) + fmt::format("unknown parameter '{}' (did you mean {}?)", name, nearest_param_name(name)));
      c.fixed.set(static_cast<size_t>(*i));
    }
  }
  if (const YAML::Node sd = root["std"]) {
    const std::string sp = join(keypath, "std");
    if (!sd.IsMap()) throw InputError(yaml_where(file, sd, sp) + "expected a map of parameter: 1-sigma, e.g. {la1: 0.002}");
    for (const auto& kv : sd) {
      const std::string name = kv.first.Scalar();
      const auto i = param_index(name);
      const std::string key = join(sp, name);
      if (!i) throw InputError(yaml_where(file, kv.first, key) + fmt::format("unknown parameter (did you mean {}?)", nearest_param_name(name)));
      if (c.fixed.test(static_cast<size_t>(*i)))
        throw InputError(yaml_where(file, kv.first, key) + "a fixed parameter has no 1-sigma (remove it from std or from fixed)");
      c.sigma[static_cast<size_t>(*i)] = sigma_from_yaml(kv.second, file, key, *i);
    }
  }
  if (const YAML::Node d = root["diagnostics"]) {
    const std::string dp = join(keypath, "diagnostics");
    if (!d.IsMap()) throw InputError(yaml_where(file, d, dp) + "expected a map (cost, iterations, rank, ...)");
    for (const auto& kv : d) {
      const std::string name = kv.first.IsScalar() ? kv.first.Scalar() : "";
      const std::string key = join(dp, name);
      const bool plain = !name.empty() && name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_") == std::string::npos;
      if (!plain) throw InputError(yaml_where(file, kv.first, dp) + "a diagnostics key must be a lower-case name such as cost or rank");
      const YAML::Node& v = kv.second;
      if (name == "cost" || name == "condition_number" || name == "kmrmse_mm" || name == "seconds") {
        number_or_special(v, file, key);
      } else if (name == "iterations" || name == "evaluations" || name == "rank" || name == "free_parameters") {
        yaml_integer(v, file, key, 0, 1LL << 50);
      } else if (name == "converged" || name == "rank_deficient") {
        yaml_bool(v, file, key);
      } else if (name == "method" || name == "cost_function") {
        yaml_text(v, file, key);
      } else if (name == "notes") {
        if (!v.IsSequence()) throw InputError(yaml_where(file, v, key) + "expected a list of text");
        for (size_t k = 0; k < v.size(); ++k) yaml_string(v[k], file, fmt::format("{}[{}]", key, k));
      } else if (!v.IsScalar() && !v.IsSequence()) {
        throw InputError(yaml_where(file, v, key) + "expected a number, text or list (diagnostics are kept as they are)");
      }
      std::string text = flow_text(v);
      if (text.find('\n') != std::string::npos)
        throw InputError(yaml_where(file, v, key) + "expected a value that fits on one line");
      c.diagnostics.emplace_back(name, std::move(text));
    }
  }
  return c;
}

}  // namespace

Geometry geometry_from_yaml(const YAML::Node& node, const std::string& file,
                            const std::string& keypath) {
  if (!node.IsDefined() || node.IsNull()) {
    throw InputError(fmt::format("{}: missing key '{}' (a map of the 15 parameters xa1 ya1 xa2 ya2 "
                                 "xa3 ya3 la1 la2 la3 lb1 lb2 lb3 dth1 dth2 dth3)",
                                 file, keypath));
  }
  if (!node.IsMap()) {
    throw InputError(yaml_where(file, node, keypath) +
                     "expected a map of the 15 parameters xa1 ... dth3");
  }
  Geometry g;
  std::array<bool, kNumParams> seen{};
  for (const auto& kv : node) {
    const std::string key = kv.first.Scalar();
    const auto idx = param_index(key);
    if (!idx) {
      throw InputError(yaml_where(file, kv.first, join(keypath, key)) +
                       fmt::format("unknown parameter (did you mean {}?)", nearest_param_name(key)));
    }
    const std::string path = join(keypath, key);
    const double v = yaml_number(kv.second, file, path);
    if (is_length(*idx) && !(v > 0.0)) {
      throw InputError(yaml_where(file, kv.second, path) +
                       fmt::format("link length must be positive, got {}", v));
    }
    g[*idx] = v;
    seen[static_cast<size_t>(*idx)] = true;
  }
  for (int i = 0; i < kNumParams; ++i) {
    if (!seen[static_cast<size_t>(i)]) {
      throw InputError(yaml_where(file, node, keypath) +
                       fmt::format("missing key '{}' (all 15 parameters are required)", param_name(i)));
    }
  }
  return g;
}

void validate_robot(const Robot& robot, const std::string& where) {
  for (int i = 0; i < kNumParams; ++i) {
    if (is_length(i) && !(robot.geometry[i] > 0.0)) {
      throw InputError(fmt::format("{}: geometry.{}: link length must be positive, got {}", where,
                                   param_name(i), robot.geometry[i]));
    }
  }
  try {
    inverse_kinematics(robot.geometry, robot.home, robot.branch);
  } catch (const ReachError& e) {
    throw InputError(fmt::format("{}: home ({}, {}) is not reachable with this geometry: {}", where,
                                 robot.home.x(), robot.home.y(), e.what()));
  }
}

Robot robot_from_yaml(const YAML::Node& root, const std::string& file, const std::string& keypath) {
  if (!root.IsMap()) {
    throw InputError(yaml_where(file, root, keypath) +
                     "expected a map with keys name, geometry (and optionally home, elbow, limits, data_sheet)");
  }
  // A calibration result file is also a robot file (its std, fixed, diagnostics
  // kept; the drift monitor's reading model that gpm run adds, `monitor:`, is
  // read by gpm monitor alone: run/run_spec.hpp).
  yaml_check_keys(root, file, keypath,
                  {"name", "geometry", "home", "elbow", "limits", "data_sheet", "std", "fixed", "diagnostics", "monitor"});
  Robot r;
  if (root["name"]) r.name = yaml_text(root["name"], file, join(keypath, "name"));
  r.geometry = geometry_from_yaml(root["geometry"], file, join(keypath, "geometry"));
  if (const YAML::Node home = root["home"]) {
    if (!home.IsSequence() || home.size() != 2) {
      throw InputError(yaml_where(file, home, join(keypath, "home")) +
                       "expected [x, y] in mm, e.g. [216.5, 250]");
    }
    r.home = {yaml_number(home[0], file, join(keypath, "home[0]")),
              yaml_number(home[1], file, join(keypath, "home[1]"))};
  }
  if (const YAML::Node elbow = root["elbow"]) {
    if (!elbow.IsSequence() || elbow.size() != 3) {
      throw InputError(yaml_where(file, elbow, join(keypath, "elbow")) +
                       "expected three branches, each ccw or cw, e.g. [ccw, ccw, ccw]");
    }
    for (size_t i = 0; i < 3; ++i) {
      const std::string path = fmt::format("{}[{}]", join(keypath, "elbow"), i);
      const std::string s = yaml_string(elbow[i], file, path);
      if (s == "ccw") r.branch[i] = +1;
      else if (s == "cw") r.branch[i] = -1;
      else throw InputError(yaml_where(file, elbow[i], path) + fmt::format("'{}' is not ccw or cw", s));
    }
  }
  if (const YAML::Node lim = root["limits"]) {
    const std::string lp = join(keypath, "limits");
    yaml_check_keys(lim, file, lp, {"reach_margin", "min_transmission", "min_direct"});
    if (lim["reach_margin"]) {
      r.limits.reach_margin = yaml_number(lim["reach_margin"], file, lp + ".reach_margin");
      if (r.limits.reach_margin < 0.0)
        throw InputError(yaml_where(file, lim["reach_margin"], lp + ".reach_margin") + "must be >= 0");
    }
    for (const char* key : {"min_transmission", "min_direct"}) {
      if (!lim[key]) continue;
      const double v = yaml_number(lim[key], file, lp + "." + key);
      if (v < 0.0 || v >= 1.0)
        throw InputError(yaml_where(file, lim[key], lp + "." + key) +
                         fmt::format("must be in [0, 1), got {}", v));
      (std::string_view(key) == "min_transmission" ? r.limits.min_transmission : r.limits.min_direct) = v;
    }
  }
  if (const YAML::Node sheet = root["data_sheet"]) r.data_sheet = data_sheet_from_yaml(sheet, file, join(keypath, "data_sheet"));
  if (root["std"] || root["fixed"] || root["diagnostics"]) r.calibration = calibration_from_yaml(root, file, keypath);
  validate_robot(r, keypath.empty() ? file : file + ": " + keypath);
  return r;
}

Robot parse_robot(const std::string& text, const std::string& file) {
  return robot_from_yaml(load_yaml_string(text, file), file, "");
}

Robot load_robot(const std::string& path) {
  return robot_from_yaml(load_yaml_file(path), path, "");
}

std::string geometry_to_yaml(const Geometry& g, int indent) {
  std::string out;
  const std::string pad(static_cast<size_t>(indent), ' ');
  for (int i = 0; i < kNumParams; ++i) {
    out += fmt::format("{}{}: {}\n", pad, param_name(i), format_exact(g[i]));
  }
  return out;
}

std::string robot_to_yaml(const Robot& r) {
  std::string out;
  // Always double-quoted: names like "null", "~" or "1e3" stay text.
  std::string quoted;
  for (char c : r.name) {
    if (c == '"' || c == '\\') quoted += '\\';
    quoted += c;
  }
  out += fmt::format("name: \"{}\"\n", quoted);
  out += "geometry:            # mm and rad\n";
  out += geometry_to_yaml(r.geometry, 2);
  out += fmt::format("home: [{}, {}]\n", format_exact(r.home.x()), format_exact(r.home.y()));
  out += fmt::format("elbow: [{}, {}, {}]\n", r.branch[0] > 0 ? "ccw" : "cw",
                     r.branch[1] > 0 ? "ccw" : "cw", r.branch[2] > 0 ? "ccw" : "cw");
  out += "limits:\n";
  out += fmt::format("  reach_margin: {}\n", format_exact(r.limits.reach_margin));
  out += fmt::format("  min_transmission: {}\n", format_exact(r.limits.min_transmission));
  out += fmt::format("  min_direct: {}\n", format_exact(r.limits.min_direct));
  out += data_sheet_to_yaml(r.data_sheet);
  if (r.calibration) {
    const CalibrationRecord& c = *r.calibration;
    std::string sd;
    for (int i = 0; i < kNumParams; ++i) {
      if (const auto& v = c.sigma[static_cast<size_t>(i)]) sd += fmt::format("  {}: {}\n", param_name(i), number_text(sigma_for_file(*v, i)));
    }
    out += sd.empty() ? "std: {}\n" : "std:                 # 1-sigma of each estimated parameter\n" + sd;
    std::string fixed;
    for (int i = 0; i < kNumParams; ++i) {
      if (c.fixed.test(static_cast<size_t>(i))) fixed += fmt::format("{}{}", fixed.empty() ? "" : ", ", param_name(i));
    }
    out += fmt::format("fixed: [{}]\n", fixed);
    out += c.diagnostics.empty() ? "diagnostics: {}\n" : "diagnostics:\n";
    for (const auto& [key, value] : c.diagnostics) out += fmt::format("  {}: {}\n", key, value);
  }
  return out;
}

void write_file_atomic(const std::string& path, const std::string& text) {
  write_output_file(path, text);  // models/output_file.hpp: the output policy
}

void save_robot(const Robot& robot, const std::string& path) {
  write_file_atomic(path, robot_to_yaml(robot));
}

}  // namespace gpm
