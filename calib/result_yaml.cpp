#include "calib/result_yaml.hpp"

#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "models/errors.hpp"
#include "models/robot_yaml.hpp"
#include "models/yaml_util.hpp"

namespace gpm::calib {
namespace {

std::string number(double x) {
  if (std::isnan(x)) return ".nan";
  if (std::isinf(x)) return x > 0 ? ".inf" : "-.inf";
  return format_exact(x);
}

std::string quoted(const std::string& s) {
  YAML::Emitter e;
  e << YAML::DoubleQuoted << s;
  return e.c_str();
}

// A number that may also be .nan / .inf (diagnostics and std may carry them).
double number_or_special(const YAML::Node& n, const std::string& file, const std::string& key) {
  // null: JSON's not-a-number (gpm calibrate --json, docs/FORMATS.md).
  if (n.IsNull()) return std::numeric_limits<double>::quiet_NaN();
  if (n.IsScalar()) {
    const std::string s = n.Scalar();
    if (s == ".nan" || s == ".NaN" || s == ".NAN") return std::numeric_limits<double>::quiet_NaN();
    if (s == ".inf" || s == ".Inf" || s == "+.inf") return std::numeric_limits<double>::infinity();
  }
  return yaml_number(n, file, key);
}

}  // namespace

std::string result_to_yaml(const Result& r, const std::string& robot_name) {
  std::string out;
  out += "# gpm calibrate result: mm and rad (docs/FORMATS.md)\n";
  out += fmt::format("name: {}\n", quoted(robot_name));
  out += "geometry:            # all 15 parameters, estimated and fixed\n";
  out += geometry_to_yaml(r.geometry, 2);
  std::string sd;
  for (int i = 0; i < kNumParams; ++i) {
    // A parameter without a usable 1-sigma (too few samples, a singular
    // Jacobian: the notes say why; or one beyond the bounds a reader accepts)
    // is left out, so that the file, and its JSON, stays a robot file (issue 36.5).
    const double sd_i = sigma_for_file(r.sigma[static_cast<size_t>(i)], i);
    if (!r.free.test(static_cast<size_t>(i)) || !std::isfinite(sd_i)) continue;
    sd += fmt::format("  {}: {}\n", param_name(i), number(sd_i));
  }
  out += sd.empty() ? "std: {}\n" : "std:                 # 1-sigma of each estimated parameter\n" + sd;
  out += "fixed: [";
  bool first = true;
  for (int i = 0; i < kNumParams; ++i) {
    if (r.free.test(static_cast<size_t>(i))) continue;
    out += fmt::format("{}{}", first ? "" : ", ", param_name(i));
    first = false;
  }
  out += "]\n";
  out += "diagnostics:\n";
  out += fmt::format("  method: {}\n", quoted(r.method));
  out += fmt::format("  cost_function: {}\n", cost_name(r.cost));
  out += fmt::format("  cost: {}\n", number(r.final_cost));
  out += fmt::format("  iterations: {}\n", r.iterations);
  out += fmt::format("  evaluations: {}\n", r.evaluations);
  out += fmt::format("  rank: {}\n", r.rank);
  out += fmt::format("  free_parameters: {}\n", r.free.count());
  out += fmt::format("  condition_number: {}\n", number(r.condition_number));
  if (r.kmrmse_mm) out += fmt::format("  kmrmse_mm: {}\n", number(*r.kmrmse_mm));
  out += fmt::format("  seconds: {}\n", number(r.seconds));
  out += fmt::format("  converged: {}\n", r.converged ? "true" : "false");
  out += fmt::format("  rank_deficient: {}\n", r.rank_deficient ? "true" : "false");
  if (r.notes.empty()) {
    out += "  notes: []\n";
  } else {
    out += "  notes:\n";
    for (const auto& n : r.notes) out += fmt::format("    - {}\n", quoted(n));
  }
  return out;
}

void save_result(const Result& r, const std::string& robot_name, const std::string& path) {
  write_file_atomic(path, result_to_yaml(r, robot_name));
}

namespace {

// The result held by the YAML document root of file.
Result result_from_yaml(const YAML::Node& root, const std::string& file);

}  // namespace

Result parse_result(const std::string& text, const std::string& file) {
  return result_from_yaml(load_yaml_string(text, file), file);
}

namespace {

Result result_from_yaml(const YAML::Node& root, const std::string& file) {
  if (!root.IsMap()) throw InputError(fmt::format("{}: expected a calibration result map (geometry, std, fixed, diagnostics)", file));
  yaml_check_keys(root, file, "", {"name", "geometry", "std", "fixed", "diagnostics"});
  Result r;
  r.geometry = geometry_from_yaml(root["geometry"], file, "geometry");
  r.sigma.fill(std::numeric_limits<double>::quiet_NaN());
  r.free.set();
  if (const YAML::Node fixed = root["fixed"]) {
    if (!fixed.IsSequence()) throw InputError(yaml_where(file, fixed, "fixed") + "expected a list of parameter names, e.g. [xa1, ya1, xa2, ya2]");
    for (size_t k = 0; k < fixed.size(); ++k) {
      const std::string key = fmt::format("fixed[{}]", k);
      const std::string name = yaml_string(fixed[k], file, key);
      const auto i = param_index(name);
      if (!i) throw InputError(yaml_where(file, fixed[k], key) + fmt::format("unknown parameter '{}' (did you mean {}?)", name, nearest_param_name(name)));
      r.free.reset(static_cast<size_t>(*i));
    }
  }
  if (const YAML::Node sd = root["std"]) {
    if (!sd.IsMap()) throw InputError(yaml_where(file, sd, "std") + "expected a map of parameter: 1-sigma");
    for (const auto& kv : sd) {
      const std::string name = kv.first.Scalar();
      const auto i = param_index(name);
      if (!i) throw InputError(yaml_where(file, kv.first, "std." + name) + fmt::format("unknown parameter (did you mean {}?)", nearest_param_name(name)));
      if (!r.free.test(static_cast<size_t>(*i))) throw InputError(yaml_where(file, kv.first, "std." + name) + "a fixed parameter has no 1-sigma (remove it from std or from fixed)");
      r.sigma[static_cast<size_t>(*i)] = sigma_from_yaml(kv.second, file, "std." + name, *i);
    }
  }
  if (const YAML::Node d = root["diagnostics"]) {
    if (!d.IsMap()) throw InputError(yaml_where(file, d, "diagnostics") + "expected a map");
    if (d["method"]) r.method = yaml_string(d["method"], file, "diagnostics.method");
    if (d["cost_function"]) {
      const std::string c = yaml_string(d["cost_function"], file, "diagnostics.cost_function");
      const auto cost = parse_cost(c);
      if (!cost) throw InputError(yaml_where(file, d["cost_function"], "diagnostics.cost_function") + fmt::format("'{}' is not one of j1, j2, j3, ml", c));
      r.cost = *cost;
    }
    if (d["cost"]) r.final_cost = number_or_special(d["cost"], file, "diagnostics.cost");
    if (d["iterations"]) r.iterations = static_cast<long>(yaml_integer(d["iterations"], file, "diagnostics.iterations", 0, 1LL << 40));
    if (d["evaluations"]) r.evaluations = static_cast<long>(yaml_integer(d["evaluations"], file, "diagnostics.evaluations", 0, 1LL << 50));
    if (d["rank"]) r.rank = static_cast<int>(yaml_integer(d["rank"], file, "diagnostics.rank", 0, kNumParams));
    if (d["condition_number"]) r.condition_number = number_or_special(d["condition_number"], file, "diagnostics.condition_number");
    if (d["kmrmse_mm"]) r.kmrmse_mm = number_or_special(d["kmrmse_mm"], file, "diagnostics.kmrmse_mm");
    if (d["seconds"]) r.seconds = number_or_special(d["seconds"], file, "diagnostics.seconds");
    if (d["converged"]) r.converged = yaml_bool(d["converged"], file, "diagnostics.converged");
    if (d["rank_deficient"]) r.rank_deficient = yaml_bool(d["rank_deficient"], file, "diagnostics.rank_deficient");
    if (const YAML::Node notes = d["notes"]) {
      for (size_t k = 0; k < notes.size(); ++k) r.notes.push_back(yaml_string(notes[k], file, fmt::format("diagnostics.notes[{}]", k)));
    }
  }
  return r;
}

}  // namespace

Result load_result(const std::string& path) { return result_from_yaml(load_yaml_file(path), path); }

Robot usable_robot(const Robot& base, const Geometry& calibrated) {
  Robot r = base;
  r.geometry = calibrated;
  try {
    validate_robot(r, "the calibrated geometry");
  } catch (const InputError& e) {
    throw Error(fmt::format("{}; it is not a usable robot, so the calibration failed (do the samples determine "
                            "every free parameter? spread them over the workspace)",
                            e.what()));
  }
  return r;
}

Robot robot_from_result(const std::string& path, const Robot& base) {
  Robot r = base;
  r.geometry = load_result(path).geometry;
  validate_robot(r, path);
  return r;
}

}  // namespace gpm::calib
