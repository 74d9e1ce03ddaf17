#include "run/run_spec.hpp"

#include "calib/calibrate.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>

#include <fmt/format.h>

#include "models/bounds.hpp"
#include "models/errors.hpp"
#include "models/rng.hpp"
#include "models/yaml_util.hpp"

namespace gpm::scenario {
namespace {

Eigen::Vector2d point(const YAML::Node& n, const std::string& file, const std::string& key) {
  if (!n.IsSequence() || n.size() != 2) {
    throw InputError(yaml_where(file, n, key) + "expected [x, y] in mm");
  }
  return {yaml_number(n[0], file, key + "[0]"), yaml_number(n[1], file, key + "[1]")};
}

// A number or a list of three (one per joint), each in [0, hi] (unit: what it is in).
std::array<double, 3> per_joint(const YAML::Node& n, const std::string& file, const std::string& key, double hi,
                                const char* unit) {
  return yaml_number_or_three(n, file, key, "a number or a list of three (one per joint)",
                              [&](const YAML::Node& v, const std::string& k) {
                                const double x = yaml_number(v, file, k);
                                if (!(x >= 0.0 && x <= hi))
                                  throw InputError(yaml_where(file, v, k) +
                                                   fmt::format("{} is out of range (valid: 0 to {} {})", x, hi, unit));
                                return x;
                              });
}

// calibration.drive_friction, or (with_scale false: no fit_scale or from_balance key) monitor.drive_friction;
// a key left out keeps its value in f.
DriveFriction parse_drive_friction(const YAML::Node& n, const std::string& file, const std::string& key,
                                   DriveFriction f, bool with_scale) {
  if (!n.IsMap())
    throw InputError(yaml_where(file, n, key) +
                     (with_scale ? "expected {coulomb_Nm: N m, viscous_Nm_s: N m s/rad, fit_scale: bool, from_balance: bool, weigh_rest: bool, weigh_signs: bool, max_skew_correlation: 0 to 1} (each friction a number or a list of three)"
                                 : "expected {coulomb_Nm: N m, viscous_Nm_s: N m s/rad} (each a number or a list of three)"));
  if (with_scale)
    yaml_check_keys(n, file, key, {"coulomb_Nm", "viscous_Nm_s", "fit_scale", "from_balance", "weigh_rest", "weigh_signs",
                                   "max_skew_correlation"});
  else
    yaml_check_keys(n, file, key, {"coulomb_Nm", "viscous_Nm_s"});
  if (n["coulomb_Nm"]) f.coulomb_Nm = per_joint(n["coulomb_Nm"], file, key + ".coulomb_Nm", 20.0, "N m");
  if (with_scale && n["fit_scale"]) f.fit_scale = yaml_bool(n["fit_scale"], file, key + ".fit_scale");
  if (with_scale && n["from_balance"]) f.from_balance = yaml_bool(n["from_balance"], file, key + ".from_balance");
  if (with_scale && n["weigh_rest"]) f.weigh_rest = yaml_bool(n["weigh_rest"], file, key + ".weigh_rest");
  if (with_scale && n["weigh_signs"]) f.weigh_signs = yaml_bool(n["weigh_signs"], file, key + ".weigh_signs");
  if (with_scale && n["max_skew_correlation"])
    f.max_skew_correlation =
        yaml_within(n["max_skew_correlation"], file, key + ".max_skew_correlation", limits::kSkewCorrelation);
  if (n["viscous_Nm_s"]) f.viscous_Nm_s = per_joint(n["viscous_Nm_s"], file, key + ".viscous_Nm_s", 100.0, "N m s/rad");
  return f;
}

// Latch skew: a number (encoders 2 and 3; encoder 1 is the reference) or a
// list of three, each within +-0.01 s (sim/effects_yaml.cpp's encoder_skew_s).
std::array<double, 3> skew_list(const YAML::Node& n, const std::string& file, const std::string& key) {
  return yaml_number_or_three(
      n, file, key, "a number (encoders 2 and 3) or a list of three",
      [&](const YAML::Node& v, const std::string& k) {
        const double x = yaml_number(v, file, k);
        if (!(std::abs(x) <= 0.01))
          throw InputError(yaml_where(file, v, k) + fmt::format("{} s is out of range (valid: -0.01 to 0.01 s)", x));
        return x;
      },
      [](double s) { return std::array<double, 3>{0.0, s, s}; });
}

// monitor.harmonic_rad: four lists of six (a1 a2 a3 b1 b2 b3, rad), one per
// order: once per joint revolution, once and twice per motor revolution, the
// motor's cogging (the data sheet's cogging_periods per motor revolution);
// three lists (no cogging) are read as well.
std::array<std::array<double, 6>, calib::kHarmonicOrders> harmonic_orders(const YAML::Node& n, const std::string& file,
                                                                          const std::string& key) {
  const std::string expected = "expected four lists of six numbers (a1 a2 a3 b1 b2 b3 in rad of each order: joint, "
                               "motor, twice motor revolution, cogging; the last may be left out), each within +-0.01 rad";
  if (!n.IsSequence() || (n.size() != 3 && n.size() != calib::kHarmonicOrders))
    throw InputError(yaml_where(file, n, key) + expected);
  std::array<std::array<double, 6>, calib::kHarmonicOrders> out{};
  for (std::size_t o = 0; o < n.size(); ++o) {
    const YAML::Node row = n[o];
    const std::string k = fmt::format("{}[{}]", key, o);
    if (!row.IsSequence() || row.size() != 6) throw InputError(yaml_where(file, row, k) + expected);
    for (std::size_t c = 0; c < 6; ++c) {
      const double x = yaml_number(row[c], file, fmt::format("{}[{}]", k, c));
      if (!(std::abs(x) <= 0.01)) throw InputError(yaml_where(file, row[c], k) + expected);
      out[o][c] = x;
    }
  }
  return out;
}

MonitorReadingModel reading_model_preset(const YAML::Node& n, const std::string& file, const std::string& key,
                                         const DataSheet& sheet) {
  const std::string name = yaml_string(n, file, key);
  if (name == "ideal") return ideal_reading_model();
  if (name == "data_sheet") return data_sheet_reading_model(sheet);
  throw InputError(yaml_where(file, n, key) + fmt::format("'{}' is not a reading model preset (valid: ideal, data_sheet)", name));
}

// calibration.fix: the parameters held at their start value (a list of names, each once).
FreeMask parse_fixed(const YAML::Node& fix, const std::string& file) {
  if (!fix.IsSequence())
    throw InputError(yaml_where(file, fix, "calibration.fix") + "expected a list of parameter names, e.g. [xa1, ya1, xa2, ya2]");
  FreeMask fixed;
  for (size_t k = 0; k < fix.size(); ++k) {
    const std::string key = fmt::format("calibration.fix[{}]", k);
    const std::string name = yaml_string(fix[k], file, key);
    const auto idx = param_index(name);
    if (!idx)
      throw InputError(yaml_where(file, fix[k], key) +
                       fmt::format("unknown parameter '{}' (did you mean {}?)", name, nearest_param_name(name)));
    if (fixed.test(static_cast<size_t>(*idx)))
      throw InputError(yaml_where(file, fix[k], key) + fmt::format("'{}' is listed twice; list each parameter once", name));
    fixed.set(static_cast<size_t>(*idx));
  }
  return fixed;
}

// calibration.estimate: the reading effects estimated beside the geometry (a list, each once; [] none).
void parse_estimated_effects(const YAML::Node& est, const std::string& file, CalibrationSpec& c) {
  if (!est.IsSequence())
    throw InputError(yaml_where(file, est, "calibration.estimate") +
                     "expected a list of compliance, skew, friction, clearance, encoder_error, joint_error (or [])");
  c.estimate_compliance = false;
  c.estimate_skew = false;
  c.estimate_friction = false;
  c.estimate_clearance = false;
  c.estimate_encoder_error = false;
  c.estimate_joint_error = false;
  for (size_t k = 0; k < est.size(); ++k) {
    const std::string key = fmt::format("calibration.estimate[{}]", k);
    const std::string what = yaml_string(est[k], file, key);
    for (size_t e = 0; e < k; ++e)
      if (est[e].IsScalar() && est[e].Scalar() == what)
        throw InputError(yaml_where(file, est[k], key) +
                         fmt::format("'{}' is listed twice (also calibration.estimate[{}]); list each effect once", what, e));
    if (what == "compliance") c.estimate_compliance = true;
    else if (what == "skew") c.estimate_skew = true;
    else if (what == "friction") c.estimate_friction = true;
    else if (what == "clearance") c.estimate_clearance = true;
    else if (what == "encoder_error") c.estimate_encoder_error = true;
    else if (what == "joint_error") c.estimate_joint_error = true;
    else
      throw InputError(yaml_where(file, est[k], key) +
                       fmt::format("unknown effect '{}' (valid: compliance, skew, friction, clearance, encoder_error, "
                                   "joint_error)",
                                   what));
  }
}

// calibration.start and calibration.reference_at: where the fit starts.
void parse_start(const YAML::Node& n, const std::string& file, CalibrationSpec& c) {
  if (n["start"]) {
    const std::string s = yaml_string(n["start"], file, "calibration.start");
    if (s != "nominal" && s != "reference") {
      throw InputError(yaml_where(file, n["start"], "calibration.start") +
                       fmt::format("'{}' is not nominal or reference", s));
    }
    c.start_reference = s == "reference";
  }
  if (n["reference_at"]) {
    if (!c.start_reference) {
      throw InputError(yaml_where(file, n["reference_at"], "calibration.reference_at") +
                       "needs start: reference (it says where the reference readings are taken)");
    }
    c.reference_at = point(n["reference_at"], file, "calibration.reference_at");
  }
}

CalibrationSpec parse_calibration(const YAML::Node& n, const std::string& file, const DataSheet& sheet) {
  CalibrationSpec c;
  c.drive_friction = stated_drive_friction(sheet);
  for (int i : {kXa1, kYa1, kXa2, kYa2}) c.fixed.set(static_cast<size_t>(i));
  if (!n) return c;
  yaml_check_keys(n, file, "calibration",
                  {"cost", "method", "fix", "budget", "seed", "sigma", "allow_rank_deficient", "start", "reference_at", "estimate", "loss", "tension_min_N",
                   "crossing_s", "drive_friction"});
  if (n["cost"]) {
    const std::string s = yaml_string(n["cost"], file, "calibration.cost");
    const auto cost = calib::parse_cost(s);
    if (!cost) throw InputError(yaml_where(file, n["cost"], "calibration.cost") +
                                fmt::format("unknown cost '{}' (valid: j1, j2, j3, ml)", s));
    c.cost = *cost;
  }
  if (n["method"]) {
    const std::string where = yaml_where(file, n["method"], "calibration.method");
    c.method = calib::parse_method(yaml_string(n["method"], file, "calibration.method"),
                                   where.substr(0, where.size() - 2));  // calib adds ": unknown method ..."
  }
  if (const YAML::Node fix = n["fix"]) c.fixed = parse_fixed(fix, file);
  // The budget counts LM iterations or a global method's evaluations, each
  // with its bound (docs/CLI.md, Limits; issue 36.8).
  if (n["budget"]) {
    c.budget = static_cast<long>(yaml_within(n["budget"], file, "calibration.budget",
                                             c.method == calib::Method::kLM ? limits::kLmIterations : limits::kEvaluations));
    if (c.method == calib::Method::kLM) c.lm_iterations = static_cast<int>(c.budget);
  }
  if (n["seed"]) c.seed = static_cast<std::uint64_t>(yaml_within(n["seed"], file, "calibration.seed", limits::kSeed));
  if (n["sigma"]) c.sigma = yaml_within(n["sigma"], file, "calibration.sigma", limits::kEncoderSigma);
  if (n["tension_min_N"]) {
    c.tension_min_N = yaml_positive(n["tension_min_N"], file, "calibration.tension_min_N");
    if (*c.tension_min_N > 100.0)
      throw InputError(yaml_where(file, n["tension_min_N"], "calibration.tension_min_N") +
                       fmt::format("{} N leaves no sample of a GPM2002 (valid: 0 < N <= 100)", *c.tension_min_N));
  }
  if (n["crossing_s"]) c.crossing_s = yaml_within(n["crossing_s"], file, "calibration.crossing_s", limits::kCrossingTime);
  if (n["drive_friction"])
    c.drive_friction = parse_drive_friction(n["drive_friction"], file, "calibration.drive_friction",
                                            c.drive_friction, true);
  if (const YAML::Node est = n["estimate"]) parse_estimated_effects(est, file, c);
  if (n["loss"]) {
    try {
      c.loss = calib::parse_loss(yaml_string(n["loss"], file, "calibration.loss"), "calibration.loss");
    } catch (const InputError& e) {
      throw InputError(yaml_where(file, n["loss"], "") + e.what());
    }
  }
  if (n["allow_rank_deficient"]) c.allow_rank_deficient = yaml_bool(n["allow_rank_deficient"], file, "calibration.allow_rank_deficient");
  parse_start(n, file, c);
  return c;
}


CompensationPlan parse_compensation(const YAML::Node& n, const std::string& file, const sim::Scenario& s) {
  CompensationPlan plan;
  const Eigen::Vector2d home = s.controller.home;
  plan.path = sim::CirclePath{home, 60.0, 4.0, 1.0};
  int count = 12;
  double radius = 80.0;
  Eigen::Vector2d centre = home;
  if (n) {
    yaml_check_keys(n, file, "compensation", {"path", "poses", "count", "radius", "centre", "move_speed_mm_s"});
    if (n["path"]) {
      sim::PathDefaults d;
      d.centre = home;
      plan.path = sim::path_from_yaml(n["path"], file, "compensation.path", d);
    }
    if (n["count"]) count = static_cast<int>(yaml_integer(n["count"], file, "compensation.count", 1, 10000));
    if (n["radius"]) radius = yaml_positive(n["radius"], file, "compensation.radius");
    if (n["centre"]) centre = point(n["centre"], file, "compensation.centre");
    if (n["move_speed_mm_s"]) plan.move_speed_mm_s = yaml_positive(n["move_speed_mm_s"], file, "compensation.move_speed_mm_s");
    if (const YAML::Node poses = n["poses"]) {
      if (!poses.IsSequence() || poses.size() == 0) {
        throw InputError(yaml_where(file, poses, "compensation.poses") + "expected a list of [x, y] poses");
      }
      for (size_t k = 0; k < poses.size(); ++k) {
        plan.poses.push_back(point(poses[k], file, fmt::format("compensation.poses[{}]", k)));
      }
    }
  }
  if (plan.poses.empty()) {
    // Test poses independent of the calibration samples (their own stream).
    Rng rng(derive_seed(s.seed, Stream::kTestPoses));
    plan.poses = sim::disc_poses(centre, radius, count, rng);
  }
  if (s.sampling) plan.sampling = s.sampling->options;
  return plan;
}

template <typename T>
void opt_number(const YAML::Node& n, const char* key, const std::string& file, std::optional<T>& out) {
  if (n[key]) out = yaml_positive(n[key], file, std::string("expect.") + key);
}

// expect.note_contains: a text or a list of texts (each a string).
std::vector<std::string> note_texts(const YAML::Node& v, const std::string& file) {
  if (v.IsScalar()) return {yaml_string(v, file, "expect.note_contains")};
  if (!v.IsSequence() || v.size() == 0)
    throw InputError(yaml_where(file, v, "expect.note_contains") +
                     "expected a text or a list of texts, each a note must contain");
  std::vector<std::string> out;
  for (std::size_t i = 0; i < v.size(); ++i)
    out.push_back(yaml_string(v[i], file, fmt::format("expect.note_contains[{}]", i)));
  return out;
}

Expectations parse_expect(const YAML::Node& n, const std::string& file) {
  Expectations e;
  if (!n) return e;
  yaml_check_keys(n, file, "expect",
                  {"converged", "error", "cost_max", "kmrmse_mm_max", "crb_ratio_max", "sigma_ratio_max", "static_rms_um_max",
                   "path_rms_um_max", "improvement_min", "refused_contains", "note_contains", "floor_ratio_max",
                   "robot_time_s_max", "model_test_passes", "positioning_rms_um_max"});
  if (n["converged"]) e.converged = yaml_bool(n["converged"], file, "expect.converged");
  if (const YAML::Node err = n["error"]) {
    if (!err.IsMap()) throw InputError(yaml_where(file, err, "expect.error") + "expected a map of tolerances");
    for (const auto& kv : err) {
      const std::string key = kv.first.Scalar();
      const std::string path = "expect.error." + key;
      const double v = yaml_positive(kv.second, file, path);
      if (key == "base_mm") e.base_mm = v;
      else if (key == "link_mm") e.link_mm = v;
      else if (key == "offset_rad") e.offset_rad = v;
      else if (const auto idx = param_index(key)) e.param[static_cast<size_t>(*idx)] = v;
      else {
        throw InputError(yaml_where(file, kv.first, path) +
                         fmt::format("unknown tolerance (did you mean {}?); valid: base_mm, link_mm, offset_rad, or a parameter name",
                                     edit_distance(key, "base_mm") < 3 ? "base_mm" : nearest_param_name(key)));
      }
    }
  }
  opt_number(n, "cost_max", file, e.cost_max);
  opt_number(n, "kmrmse_mm_max", file, e.kmrmse_mm_max);
  opt_number(n, "crb_ratio_max", file, e.crb_ratio_max);
  opt_number(n, "sigma_ratio_max", file, e.sigma_ratio_max);
  opt_number(n, "static_rms_um_max", file, e.static_rms_um_max);
  opt_number(n, "path_rms_um_max", file, e.path_rms_um_max);
  opt_number(n, "improvement_min", file, e.improvement_min);
  opt_number(n, "floor_ratio_max", file, e.floor_ratio_max);
  opt_number(n, "robot_time_s_max", file, e.robot_time_s_max);
  opt_number(n, "positioning_rms_um_max", file, e.positioning_rms_um_max);
  if (n["model_test_passes"]) e.model_test_passes = yaml_bool(n["model_test_passes"], file, "expect.model_test_passes");
  if (n["refused_contains"]) e.refused_contains = yaml_string(n["refused_contains"], file, "expect.refused_contains");
  if (const YAML::Node v = n["note_contains"]) e.note_contains = note_texts(v, file);
  return e;
}

RunSpec from_root(const YAML::Node& root, const std::string& file, const std::string& base_dir) {
  RunSpec spec;
  spec.sim = sim::scenario_from_yaml(root, file, base_dir);
  // What the procedures assume by default is the controller's robot's data
  // sheet (models/data_sheet.hpp), never the twin's truth (spec.sim.twin).
  const DataSheet& sheet = spec.sim.controller.data_sheet;
  spec.calibration = parse_calibration(root["calibration"], file, sheet);
  spec.monitor = parse_monitor_reading_model(root["monitor"], file, sheet);
  if (const YAML::Node hw = root["hardware"]) {
    const std::string h = yaml_string(hw, file, "hardware");
    spec.hardware = (std::filesystem::path(h).is_absolute() ? std::filesystem::path(h)
                                                            : std::filesystem::path(base_dir) / h).string();
  }
  if (const YAML::Node out = root["outputs"]) {
    yaml_check_keys(out, file, "outputs", {"report", "compensation"});
    if (out["report"]) spec.outputs.report = yaml_bool(out["report"], file, "outputs.report");
    if (out["compensation"]) spec.outputs.compensation = yaml_bool(out["compensation"], file, "outputs.compensation");
  }
  if (!spec.sim.sampling) {
    throw InputError(fmt::format("{}: sampling: gpm run needs a sampling plan (the calibration samples)", file));
  }
  if (spec.outputs.compensation) spec.compensation = parse_compensation(root["compensation"], file, spec.sim);
  spec.expect = parse_expect(root["expect"], file);
  return spec;
}

}  // namespace

DriveFriction stated_drive_friction(const DataSheet& sheet) {
  DriveFriction f;
  f.coulomb_Nm.fill(sheet.coulomb_Nm.nominal);
  f.viscous_Nm_s.fill(sheet.viscous_Nm_s.nominal);
  return f;
}

MonitorReadingModel ideal_reading_model() { return MonitorReadingModel{}; }

MonitorReadingModel data_sheet_reading_model(const DataSheet& sheet) {
  MonitorReadingModel m;
  calib::ReadingModel& r = m.reading;
  r.cyclic_rad.fill(sheet.encoder_accuracy_rad.nominal);
  r.clearance_mm.fill(2.0 * sheet.clearance_mm.nominal);  // both pins' radial clearance
  const DriveFriction f = stated_drive_friction(sheet);
  r.load.coulomb_Nm = f.coulomb_Nm;
  r.load.viscous_Nm_s = f.viscous_Nm_s;
  // Encoder 1 is the reference; drive i latches i - 1 bus slots after it.
  for (std::size_t i = 0; i < 3; ++i) r.skew_s[i] = static_cast<double>(i) * sheet.latch_skew_s.nominal;
  r.compliance_rad_per_Nm.fill(sheet.compliance_rad_per_Nm());
  r.gear_ratio = sheet.gear_ratio;
  r.cogging_periods = sheet.cogging_periods;
  m.thermal_time_constant_s = sheet.warm_up_time_constant_s.nominal;
  return m;
}

MonitorReadingModel parse_monitor_reading_model(const YAML::Node& n, const std::string& file, const DataSheet& sheet) {
  if (!n) return data_sheet_reading_model(sheet);
  if (n.IsScalar()) return reading_model_preset(n, file, "monitor", sheet);
  if (!n.IsMap())
    throw InputError(yaml_where(file, n, "monitor") +
                     "expected a preset (ideal, data_sheet) or a map of the monitor's reading model (see scenarios/SCHEMA.md)");
  yaml_check_keys(n, file, "monitor",
                  {"preset", "encoder_cyclic_rad", "clearance_mm", "drive_friction", "skew_s", "compliance_rad_per_Nm",
                   "backlash_rad", "harmonic_rad", "reducer_home_rad", "thermal_time_constant_s", "learning_s", "scale_floor",
                   "map_radius_rad"});
  MonitorReadingModel m =
      n["preset"] ? reading_model_preset(n["preset"], file, "monitor.preset", sheet) : data_sheet_reading_model(sheet);
  calib::ReadingModel& r = m.reading;
  if (n["encoder_cyclic_rad"]) r.cyclic_rad = per_joint(n["encoder_cyclic_rad"], file, "monitor.encoder_cyclic_rad", 0.01, "rad");
  if (n["clearance_mm"]) {
    r.clearance_mm = per_joint(n["clearance_mm"], file, "monitor.clearance_mm", 1.0, "mm");
    for (double& d : r.clearance_mm) d *= 2.0;  // both pins' radial clearance: the link's play
  }
  if (n["drive_friction"]) {
    const DriveFriction f = parse_drive_friction(n["drive_friction"], file, "monitor.drive_friction",
                                                 DriveFriction{r.load.coulomb_Nm, r.load.viscous_Nm_s, false}, false);
    r.load.coulomb_Nm = f.coulomb_Nm;
    r.load.viscous_Nm_s = f.viscous_Nm_s;
  }
  if (n["skew_s"]) r.skew_s = skew_list(n["skew_s"], file, "monitor.skew_s");
  if (n["compliance_rad_per_Nm"])
    r.compliance_rad_per_Nm = per_joint(n["compliance_rad_per_Nm"], file, "monitor.compliance_rad_per_Nm", 1.0, "rad/N m");
  if (n["backlash_rad"]) r.backlash_rad = per_joint(n["backlash_rad"], file, "monitor.backlash_rad", 0.01, "rad");
  if (const YAML::Node h = n["harmonic_rad"]) r.harmonic = harmonic_orders(h, file, "monitor.harmonic_rad");
  if (const YAML::Node h = n["reducer_home_rad"])
    r.reducer_home_rad = per_joint(h, file, "monitor.reducer_home_rad", 2.0 * std::numbers::pi, "rad");
  if (const YAML::Node t = n["thermal_time_constant_s"]) {
    const double tau = yaml_number(t, file, "monitor.thermal_time_constant_s");
    if (!(tau >= 1.0 && tau <= 1e6))
      throw InputError(yaml_where(file, t, "monitor.thermal_time_constant_s") +
                       fmt::format("{} s is out of range (valid: 1 to 1e6 s)", tau));
    m.thermal_time_constant_s = tau;
  }
  if (const YAML::Node t = n["learning_s"]) {
    const double v = yaml_number(t, file, "monitor.learning_s");
    if (!(v >= 0.0 && v <= 10.0))
      throw InputError(yaml_where(file, t, "monitor.learning_s") + fmt::format("{} s is out of range (valid: 0 to 10 s)", v));
    m.learning_s = v;
  }
  if (const YAML::Node t = n["scale_floor"]) {
    const double v = yaml_number(t, file, "monitor.scale_floor");
    if (!(v >= 1.0 && v <= 1e3))
      throw InputError(yaml_where(file, t, "monitor.scale_floor") + fmt::format("{} is out of range (valid: 1 to 1000)", v));
    m.scale_floor = v;
  }
  if (const YAML::Node t = n["map_radius_rad"]) {
    const double v = yaml_number(t, file, "monitor.map_radius_rad");
    if (!(v >= 0.0 && v <= 0.1))
      throw InputError(yaml_where(file, t, "monitor.map_radius_rad") +
                       fmt::format("{} rad is out of range (valid: 0 to 0.1 rad; 0: no map)", v));
    m.map_radius_rad = v;
  }
  return m;
}

std::string monitor_reading_model_yaml(const MonitorReadingModel& m) {
  const auto three = [](const std::array<double, 3>& v) {
    return fmt::format("[{}, {}, {}]", format_exact(v[0]), format_exact(v[1]), format_exact(v[2]));
  };
  const calib::ReadingModel& r = m.reading;
  const std::array<double, 3> pin = calib::pin_clearance_mm(r);  // the YAML states each pin's radial clearance
  std::string harmonics;
  for (const auto& h : r.harmonic) {
    harmonics += harmonics.empty() ? "[" : ", ";
    harmonics += "[";
    for (std::size_t c = 0; c < h.size(); ++c) harmonics += (c ? ", " : "") + format_exact(h[c]);
    harmonics += "]";
  }
  return fmt::format(
      "monitor:             # the drift monitor's reading model (gpm monitor --model reads it; scenario key monitor:)\n"
      "  encoder_cyclic_rad: {}\n  clearance_mm: {}\n"
      "  drive_friction: {{coulomb_Nm: {}, viscous_Nm_s: {}}}\n"
      "  skew_s: {}\n  compliance_rad_per_Nm: {}\n  backlash_rad: {}\n  harmonic_rad: {}]\n{}"
      "  thermal_time_constant_s: {}\n  learning_s: {}\n  scale_floor: {}\n  map_radius_rad: {}\n",
      three(r.cyclic_rad), three(pin), three(r.load.coulomb_Nm), three(r.load.viscous_Nm_s), three(r.skew_s),
      three(r.compliance_rad_per_Nm), three(r.backlash_rad), harmonics,
      std::ranges::all_of(r.reducer_home_rad, [](double v) { return std::isfinite(v); })
          ? fmt::format("  reducer_home_rad: {}\n", three(r.reducer_home_rad))
          : std::string(),
      format_exact(m.thermal_time_constant_s),
      format_exact(m.learning_s), format_exact(m.scale_floor), format_exact(m.map_radius_rad));
}

RunSpec parse_run_spec(const std::string& text, const std::string& file, const std::string& base_dir) {
  return from_root(load_yaml_string(text, file), file, base_dir);
}

RunSpec load_run_spec(const std::string& path) {
  const std::string base = std::filesystem::path(path).parent_path().string();
  return from_root(load_yaml_file(path), path, base.empty() ? "." : base);
}

}  // namespace gpm::scenario
