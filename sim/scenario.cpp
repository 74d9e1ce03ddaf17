#include "sim/scenario.hpp"
#include "models/data_dir.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "models/bounds.hpp"
#include "models/errors.hpp"
#include "models/kinematics.hpp"
#include "models/robot_yaml.hpp"
#include "models/pose_layouts.hpp"
#include "models/rng.hpp"
#include "models/yaml_util.hpp"
#include "sim/effects_yaml.hpp"
#include "sim/effects_random.hpp"

namespace gpm::sim {
namespace {

// Bounds of counts (scenarios/SCHEMA.md): poses in one plan, and rows of the
// trajectory log (120 bytes each in memory: 2e7 rows is about 2.4 GB).
constexpr long long kMaxPoses = 10000;
constexpr double kMaxLogRows = 2e7;
// Default rate of the trajectory log (trajectory.csv): ample for figures and
// 30 fps video, a tenth to a fortieth of the servo rate (log.every: 1 for all).
constexpr double kDefaultLogRateHz = 200.0;

// Everything a key needs to report an error.
struct Ctx {
  const std::string& file;
  std::string path;
  Ctx at(const std::string& key) const { return {file, path.empty() ? key : path + "." + key}; }
};

[[noreturn]] void fail(const Ctx& c, const YAML::Node& n, const std::string& what) {
  throw InputError(yaml_where(c.file, n, c.path) + what);
}

double number(const YAML::Node& n, const Ctx& c) { return yaml_number(n, c.file, c.path); }
double positive(const YAML::Node& n, const Ctx& c) { return yaml_positive(n, c.file, c.path); }

double non_negative(const YAML::Node& n, const Ctx& c) {
  const double v = number(n, c);
  if (v < 0.0) fail(c, n, fmt::format("must be zero or positive, got {}", v));
  return v;
}

Eigen::Vector2d point(const YAML::Node& n, const Ctx& c) {
  if (!n.IsSequence() || n.size() != 2) fail(c, n, "expected [x, y] in mm, e.g. [216.5, 250]");
  return {number(n[0], c.at("[0]")), number(n[1], c.at("[1]"))};
}

// Optional positive number; keeps the default when absent.
void opt_positive(const YAML::Node& map, const char* key, const Ctx& c, double& out) {
  if (map[key]) out = positive(map[key], c.at(key));
}

// A number in [lo, hi] (unit and reason for the range in the message; issue
// 14.8/14.9: every duration, speed and tolerance has a physical range).
double bounded(const YAML::Node& n, const Ctx& c, double lo, double hi, const char* unit) {
  const double v = number(n, c);
  if (!(v >= lo && v <= hi)) fail(c, n, fmt::format("must be from {} to {} {}, got {}", lo, hi, unit, n.Scalar()));
  return v;
}

// Optional bounded number; keeps the default when absent.
void opt_bounded(const YAML::Node& map, const char* key, const Ctx& c, double lo, double hi,
                 const char* unit, double& out) {
  if (map[key]) out = bounded(map[key], c.at(key), lo, hi, unit);
}

void require(const YAML::Node& map, const char* key, const Ctx& c, const std::string& why) {
  if (!map[key]) fail(c, map, fmt::format("missing key '{}' ({})", key, why));
}

// The robot (or calibration result) file a scenario key names, relative to
// the scenario's folder; a missing file is named with the key that gave it.
Robot robot_file_at(const YAML::Node& n, const std::string& file, const std::string& key, const std::string& base_dir) {
  std::filesystem::path p = yaml_string(n, file, key);
  if (p.is_relative()) p = std::filesystem::path(base_dir) / p;
  p = p.lexically_normal();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(p, ec))
    throw InputError(yaml_where(file, n, key) +
                     fmt::format("no robot file {} (expected a robot or calibration result file, relative to the "
                                 "scenario, or a map with geometry)",
                                 p.string()));
  return load_robot(p.string());
}

ActualSpec parse_actual(const YAML::Node& n, const Ctx& c, const std::string& base_dir) {
  ActualSpec a;
  a.keep = FreeMask{}.set(kXa1).set(kYa1).set(kXa2).set(kYa2);
  if (n.IsScalar()) {
    // A robot (or calibration result) file: all 15 parameters, none perturbed.
    const Robot r = robot_file_at(n, c.file, c.path, base_dir);
    for (int i = 0; i < kNumParams; ++i) a.explicit_values[static_cast<size_t>(i)] = r.geometry[i];
    return a;
  }
  if (!n.IsMap()) {
    fail(c, n, "expected a robot file (path relative to the scenario) or a map with geometry and/or perturb");
  }
  yaml_check_keys(n, c.file, c.path, {"geometry", "perturb"});
  if (const YAML::Node g = n["geometry"]) {
    const Ctx cg = c.at("geometry");
    if (!g.IsMap()) fail(cg, g, "expected a map of parameters, e.g. {la3: 244.5, dth1: 0.01}");
    for (const auto& kv : g) {
      const std::string key = kv.first.Scalar();
      const auto idx = param_index(key);
      if (!idx) fail(cg.at(key), kv.first, fmt::format("unknown parameter (did you mean {}?)", nearest_param_name(key)));
      const double v = number(kv.second, cg.at(key));
      if (is_length(*idx) && !(v > 0.0)) fail(cg.at(key), kv.second, fmt::format("link length must be positive, got {}", v));
      a.explicit_values[static_cast<size_t>(*idx)] = v;
    }
  }
  if (const YAML::Node p = n["perturb"]) {
    const Ctx cp = c.at("perturb");
    yaml_check_keys(p, c.file, cp.path, {"base_mm", "link_mm", "offset_rad", "keep"});
    if (p["base_mm"]) a.sigma_base_mm = non_negative(p["base_mm"], cp.at("base_mm"));
    if (p["link_mm"]) a.sigma_link_mm = non_negative(p["link_mm"], cp.at("link_mm"));
    if (p["offset_rad"]) a.sigma_offset_rad = non_negative(p["offset_rad"], cp.at("offset_rad"));
    if (const YAML::Node k = p["keep"]) {
      const Ctx ck = cp.at("keep");
      if (!k.IsSequence()) fail(ck, k, "expected a list of parameter names, e.g. [xa1, ya1, xa2, ya2]");
      a.keep.reset();
      for (size_t i = 0; i < k.size(); ++i) {
        const Ctx ci{c.file, fmt::format("{}[{}]", ck.path, i)};
        const std::string name = yaml_string(k[i], c.file, ci.path);
        const auto idx = param_index(name);
        if (!idx) fail(ci, k[i], fmt::format("unknown parameter '{}' (did you mean {}?)", name, nearest_param_name(name)));
        if (a.keep.test(static_cast<size_t>(*idx)))
          fail(ci, k[i], fmt::format("'{}' is listed twice; name each kept parameter once", name));
        a.keep.set(static_cast<size_t>(*idx));
      }
    }
  }
  return a;
}

void parse_servo(const YAML::Node& n, const Ctx& c, TwinConfig& t) {
  yaml_check_keys(n, c.file, c.path,
                  {"rate_hz", "kp", "kv", "ki", "feedforward", "torque_limit", "velocity_limit", "modes", "max_tracking_mm"});
  opt_positive(n, "rate_hz", c, t.servo_rate_hz);
  ServoDrive d = t.drives[0];
  opt_positive(n, "kp", c, d.kp);
  opt_positive(n, "kv", c, d.kv);
  if (n["ki"]) d.ki = non_negative(n["ki"], c.at("ki"));
  if (n["feedforward"]) {
    d.feedforward = number(n["feedforward"], c.at("feedforward"));
    if (d.feedforward < 0.0 || d.feedforward > 1.0)
      fail(c.at("feedforward"), n["feedforward"], fmt::format("must be in [0, 1], got {}", d.feedforward));
  }
  opt_positive(n, "torque_limit", c, d.torque_limit);
  opt_positive(n, "velocity_limit", c, d.velocity_limit);
  for (auto& dr : t.drives) dr = d;
  if (const YAML::Node m = n["modes"]) {
    const Ctx cm = c.at("modes");
    if (!m.IsSequence() || m.size() != 3)
      fail(cm, m, "expected three modes, each position, torque_off or {torque: N m[, alternate_s: s]}, e.g. [position, position, torque_off]");
    int active = 0;
    for (size_t i = 0; i < 3; ++i) {
      const Ctx ci{c.file, fmt::format("{}[{}]", cm.path, i)};
      if (m[i].IsMap()) {  // {torque: N m[, alternate_s: s]}: a preload one way, or each way in turn
        yaml_check_keys(m[i], c.file, ci.path, {"torque", "alternate_s", "ramp_s"});
        if (!m[i]["torque"]) fail(ci, m[i], "expected {torque: N m}, e.g. {torque: 0.5} or {torque: 2, alternate_s: 1.2}");
        const double tq = number(m[i]["torque"], ci.at("torque"));
        if (!std::isfinite(tq) || std::abs(tq) > t.drives[i].torque_limit)
          fail(ci.at("torque"), m[i]["torque"],
               fmt::format("must be within +-torque_limit ({} N m), got {}", t.drives[i].torque_limit, tq));
        t.drives[i].mode = ServoMode::kTorque;
        t.drives[i].torque_Nm = tq;
        ServoDrive& d = t.drives[i];
        if (const YAML::Node alt = m[i]["alternate_s"]) {
          d.alternate_s = bounded(alt, ci.at("alternate_s"), 0.01, 600.0, "s");
          const double half = 0.5 * d.alternate_s;  // each change of sign within half the time between changes
          const YAML::Node ramp = m[i]["ramp_s"];
          d.ramp_s = ramp ? bounded(ramp, ci.at("ramp_s"), 0.0, half, "s") : std::min(d.ramp_s, half);
        } else if (m[i]["ramp_s"]) {
          fail(ci.at("ramp_s"), m[i]["ramp_s"], "needs alternate_s");
        }
        continue;
      }
      const std::string s = yaml_string(m[i], c.file, ci.path);
      if (s == "position") t.drives[i].mode = ServoMode::kPosition, ++active;
      else if (s == "torque_off") t.drives[i].mode = ServoMode::kTorqueOff;
      else fail(ci, m[i], fmt::format("'{}' is not position, torque_off or {{torque: N m}}", s));
    }
    if (active < 2) fail(cm, m, "at least two joints must be position-controlled (the mechanism has 2 degrees of freedom)");
  }
}

void parse_encoder(const YAML::Node& n, const Ctx& c, EncoderModel& e) {
  yaml_check_keys(n, c.file, c.path, {"bits", "noise_rad"});
  if (n["bits"]) e.bits = static_cast<int>(yaml_integer(n["bits"], c.file, c.at("bits").path, 0, 40));
  if (n["noise_rad"]) e.noise_rad = non_negative(n["noise_rad"], c.at("noise_rad"));
}

// sampling.path_margin: the planner's margins from singular poses and the reach border.
void parse_path_margin(const YAML::Node& m, const Ctx& c, PathMargin& margin) {
  const Ctx cm = c.at("path_margin");
  if (!m.IsMap())
    fail(cm, m, "expected a map {singularity, reach_mm, deviation_mm, tolerance: {base_mm, link_mm, offset_rad}}");
  yaml_check_keys(m, c.file, cm.path, {"singularity", "reach_mm", "deviation_mm", "tolerance"});
  opt_bounded(m, "singularity", cm, 0.0, 0.9, "(a normalised measure)", margin.singularity);
  opt_bounded(m, "reach_mm", cm, 0.0, 100.0, "mm", margin.reach_mm);
  opt_bounded(m, "deviation_mm", cm, 0.0, 1000.0, "mm", margin.deviation_mm);
  if (const YAML::Node t = m["tolerance"]) {
    const Ctx ct = cm.at("tolerance");
    if (!t.IsMap()) fail(ct, t, "expected a map {base_mm, link_mm, offset_rad}");
    yaml_check_keys(t, c.file, ct.path, {"base_mm", "link_mm", "offset_rad"});
    opt_bounded(t, "base_mm", ct, 0.0, 20.0, "mm", margin.tolerance.base_mm);
    opt_bounded(t, "link_mm", ct, 0.0, 20.0, "mm", margin.tolerance.link_mm);
    opt_bounded(t, "offset_rad", ct, 0.0, 0.2, "rad", margin.tolerance.offset_rad);
  }
}

// sampling.settle: when a drive counts as at rest.
void parse_settle(const YAML::Node& s, const Ctx& c, SettleCriterion& settle) {
  const Ctx cs = c.at("settle");
  yaml_check_keys(s, c.file, cs.path, {"velocity_rad_s", "hold_s", "timeout_s"});
  opt_bounded(s, "velocity_rad_s", cs, 1e-6, 1.0, "rad/s", settle.velocity_rad_s);
  opt_bounded(s, "hold_s", cs, 1e-4, 10.0, "s", settle.hold_s);
  opt_bounded(s, "timeout_s", cs, 1e-3, 60.0, "s", settle.timeout_s);
}

// sampling.criterion: worst, d, or (on the fly, whose readings along the
// path it weighs) positioning.
DesignCriterion parse_design_criterion(const YAML::Node& n, const Ctx& c, PosePattern pattern) {
  const std::string name = yaml_string(n, c.file, c.at("criterion").path);
  if (name == "worst") return DesignCriterion::kWorst;
  if (name == "d") return DesignCriterion::kD;
  if (name == "positioning" && pattern == PosePattern::kTrajectory) return DesignCriterion::kPositioning;
  if (name == "positioning")
    fail(c.at("criterion"), n, "positioning weighs the readings along an excitation path: only for pattern: trajectory "
                               "(valid here: worst, d)");
  fail(c.at("criterion"), n, fmt::format("'{}' is not worst, d or positioning", name));
}

SamplingPlan parse_sampling(const YAML::Node& n, const Ctx& c) {
  yaml_check_keys(n, c.file, c.path,
                  {"pattern", "centre", "radius", "count", "from", "to", "poses", "move_speed_mm_s",
                   "settle", "average_s", "max_speed_mm_s", "max_accel_mm_s2", "sample_every", "path_margin",
                   "offsets_first_s", "criterion"});
  SamplingPlan p;
  require(n, "pattern", c, "disc, circle, line, list, designed or trajectory");
  const std::string pat = yaml_string(n["pattern"], c.file, c.at("pattern").path);
  const auto count = [&](long long lo) {
    require(n, "count", c, "how many poses");
    return static_cast<int>(yaml_integer(n["count"], c.file, c.at("count").path, lo, kMaxPoses));
  };
  if (pat == "disc" || pat == "circle") {
    p.pattern = pat == "disc" ? PosePattern::kDisc : PosePattern::kCircle;
    if (n["centre"]) p.centre = point(n["centre"], c.at("centre"));
    require(n, "radius", c, "mm");
    p.radius = positive(n["radius"], c.at("radius"));
    p.count = count(1);
  } else if (pat == "line") {
    p.pattern = PosePattern::kLine;
    require(n, "from", c, "[x, y] in mm");
    require(n, "to", c, "[x, y] in mm");
    p.from = point(n["from"], c.at("from"));
    p.to = point(n["to"], c.at("to"));
    p.count = count(2);
  } else if (pat == "list") {
    p.pattern = PosePattern::kList;
    require(n, "poses", c, "a list of [x, y] in mm");
    const Ctx cp = c.at("poses");
    if (!n["poses"].IsSequence() || n["poses"].size() == 0) fail(cp, n["poses"], "expected a non-empty list of [x, y] in mm");
    for (size_t i = 0; i < n["poses"].size(); ++i)
      p.poses.push_back(point(n["poses"][i], Ctx{c.file, fmt::format("{}[{}]", cp.path, i)}));
  } else if (pat == "designed" || pat == "trajectory") {
    p.pattern = pat == "designed" ? PosePattern::kDesigned : PosePattern::kTrajectory;
    // At least 11 (the parameters of the default gauge); the run layer checks
    // the count against the calibration's free set.
    p.count = count(11);
    if (n["poses"]) {  // already designed (e.g. pasted from gpm design)
      const Ctx cp = c.at("poses");
      if (!n["poses"].IsSequence() || n["poses"].size() < 2) fail(cp, n["poses"], "expected a list of at least two [x, y] in mm");
      for (size_t i = 0; i < n["poses"].size(); ++i)
        p.poses.push_back(point(n["poses"][i], Ctx{c.file, fmt::format("{}[{}]", cp.path, i)}));
    }
    if (const YAML::Node m = n["path_margin"]) parse_path_margin(m, c, p.margin);
    if (n["criterion"]) p.criterion = parse_design_criterion(n["criterion"], c, p.pattern);
    if (p.pattern == PosePattern::kTrajectory) {
      opt_bounded(n, "max_speed_mm_s", c, 1.0, 1000.0, "mm/s", p.path_limits.max_speed_mm_s);
      opt_bounded(n, "max_accel_mm_s2", c, 10.0, 20000.0, "mm/s^2", p.path_limits.max_accel_mm_s2);
      p.path_limits.max_normal_mm_s2 = p.path_limits.max_accel_mm_s2;
      if (n["sample_every"])
        p.sample_every = static_cast<int>(yaml_integer(n["sample_every"], c.file, c.at("sample_every").path, 1, 1000));
      opt_bounded(n, "offsets_first_s", c, 0.0, 60.0, "s (0: none)", p.offsets_first_s);
    }
  } else {
    fail(c.at("pattern"), n["pattern"], fmt::format("'{}' is not disc, circle, line, list, designed or trajectory", pat));
  }
  for (const char* key : {"path_margin", "criterion"})
    if (p.pattern != PosePattern::kTrajectory && p.pattern != PosePattern::kDesigned && n[key])
      fail(c.at(key), n[key], "only for pattern: designed or trajectory");
  if (p.pattern != PosePattern::kTrajectory)
    for (const char* key : {"max_speed_mm_s", "max_accel_mm_s2", "sample_every", "offsets_first_s"})
      if (n[key]) fail(c.at(key), n[key], "only for pattern: trajectory");
  if (p.pattern == PosePattern::kList && p.poses.size() > static_cast<size_t>(kMaxPoses)) {
    fail(c.at("poses"), n["poses"], fmt::format("at most {} poses, got {}", kMaxPoses, p.poses.size()));
  }
  opt_bounded(n, "move_speed_mm_s", c, 1.0, 2000.0, "mm/s", p.options.move_speed_mm_s);
  opt_bounded(n, "average_s", c, 1e-4, 10.0, "s", p.options.average_s);
  if (const YAML::Node s = n["settle"]) parse_settle(s, c, p.options.settle);
  return p;
}

// A path map; keys missing from it take `defaults` when given, and are
// required otherwise.
Path parse_path(const YAML::Node& n, const Ctx& c, const PathDefaults* defaults = nullptr) {
  yaml_check_keys(n, c.file, c.path,
                  {"shape", "centre", "radius", "period_s", "revolutions", "from", "to", "duration_s"});
  auto need = [&](const char* key, const char* why) {
    if (!defaults) require(n, key, c, why);
  };
  need("shape", "circle or line");
  const std::string shape = n["shape"] ? yaml_string(n["shape"], c.file, c.at("shape").path) : "circle";
  if (shape == "circle") {
    CirclePath p;
    p.centre = n["centre"] ? point(n["centre"], c.at("centre"))
                           : (defaults ? defaults->centre : Eigen::Vector2d(216.5, 250.0));
    need("radius", "mm");
    p.radius = n["radius"] ? positive(n["radius"], c.at("radius")) : defaults->radius;
    need("period_s", "seconds per revolution");
    p.period_s = n["period_s"] ? bounded(n["period_s"], c.at("period_s"), 0.1, 600.0, "s") : defaults->period_s;
    if (n["revolutions"]) {
      p.revolutions = bounded(n["revolutions"], c.at("revolutions"), 1e-3, 100.0, "revolutions");
    }
    return p;
  }
  if (shape == "line") {
    LinePath p;
    require(n, "from", c, "[x, y] in mm");
    require(n, "to", c, "[x, y] in mm");
    need("duration_s", "seconds");
    p.from = point(n["from"], c.at("from"));
    p.to = point(n["to"], c.at("to"));
    p.duration_s = n["duration_s"] ? bounded(n["duration_s"], c.at("duration_s"), 0.01, 600.0, "s") : defaults->duration_s;
    return p;
  }
  fail(c.at("shape"), n["shape"], fmt::format("'{}' is not circle or line", shape));
}

Operation parse_operation(const YAML::Node& n, const Ctx& c) {
  yaml_check_keys(n, c.file, c.path, {"path", "duration_s"});
  require(n, "path", c, "the path the robot repeats (as the top-level path)");
  require(n, "duration_s", c, "seconds of operation");
  Operation op;
  op.path = parse_path(n["path"], c.at("path"));
  op.duration_s = bounded(n["duration_s"], c.at("duration_s"), 0.01, 86400.0, "s");
  return op;
}

// events: [{at_s, change: {PARAM: DELTA}} | {at_s, ramp: {PARAM: DELTA}, over_s}].
std::vector<GeometryEvent> parse_events(const YAML::Node& n, const Ctx& c, double duration_s) {
  if (!n.IsSequence()) fail(c, n, "expected a list of {at_s, change: {...}} or {at_s, ramp: {...}, over_s}");
  // Each event is checked every servo cycle: their count is bounded (issue 36.8).
  if (n.size() > limits::kMaxEvents)
    fail(c, n, fmt::format("{} events; at most {} in one scenario", n.size(), limits::kMaxEvents));
  std::vector<GeometryEvent> out;
  for (std::size_t k = 0; k < n.size(); ++k) {
    const Ctx ce{c.file, fmt::format("{}[{}]", c.path, k)};
    const YAML::Node e = n[k];
    if (!e.IsMap()) fail(ce, e, "expected {at_s: T, change: {PARAM: DELTA}} or {at_s: T, ramp: {...}, over_s: S}");
    yaml_check_keys(e, c.file, ce.path, {"at_s", "change", "ramp", "over_s"});
    require(e, "at_s", ce, "when the change begins, s");
    GeometryEvent ev;
    ev.at_s = bounded(e["at_s"], ce.at("at_s"), 0.0, duration_s, "s (within operation.duration_s)");
    const bool step = static_cast<bool>(e["change"]), ramp = static_cast<bool>(e["ramp"]);
    if (step == ramp) fail(ce, e, "give exactly one of change (a step) and ramp (a drift)");
    if (ramp) {
      require(e, "over_s", ce, "how long the drift lasts, s");
      ev.over_s = bounded(e["over_s"], ce.at("over_s"), 1e-3, 86400.0, "s");
    } else if (e["over_s"]) {
      fail(ce.at("over_s"), e["over_s"], "only for ramp");
    }
    const char* key = step ? "change" : "ramp";
    const Ctx cm = ce.at(key);
    const YAML::Node m = e[key];
    if (!m.IsMap() || m.size() == 0) fail(cm, m, "expected a map {PARAM: DELTA} (mm or rad)");
    for (const auto& kv : m) {
      const std::string name = kv.first.Scalar();
      const auto idx = param_index(name);
      if (!idx) fail(cm.at(name), kv.first, fmt::format("unknown parameter '{}' (did you mean {}?)", name, nearest_param_name(name)));
      const bool offset = is_offset(*idx);
      const double lim = offset ? 0.1 : 5.0;
      ev.delta[static_cast<std::size_t>(*idx)] = bounded(kv.second, cm.at(name), -lim, lim, offset ? "rad" : "mm");
    }
    out.push_back(ev);
  }
  return out;
}

// Refuses a run whose trajectory log could outgrow memory: an upper bound of
// its rows, count x (longest move + settle timeout + average) + path duration,
// at the servo rate / log.every, against kMaxLogRows (120 bytes a row in memory).
void check_log_size(const Scenario& s, const YAML::Node& root, const Ctx& c) {
  const double rows_per_s = s.twin.servo_rate_hz / s.log_every;
  // Every move stays inside the box of home, the poses and the path start (its
  // diagonal bounds the length of any move).
  Eigen::Vector2d lo = s.controller.home, hi = s.controller.home;
  const auto grow = [&](const Eigen::Vector2d& a) { lo = lo.cwiseMin(a), hi = hi.cwiseMax(a); };
  if (s.path) grow(path_at(*s.path, 0.0).p);
  double speed = 100.0;  // of the move to the path start without sampling (sim/simulate.cpp)
  double seconds = 0.0;
  if (s.sampling) {
    const SamplingPlan& p = *s.sampling;
    if (p.pattern == PosePattern::kDisc || p.pattern == PosePattern::kCircle) {
      grow(p.centre - Eigen::Vector2d::Constant(p.radius));
      grow(p.centre + Eigen::Vector2d::Constant(p.radius));
    } else {
      grow(p.from), grow(p.to);
      for (const auto& q : p.poses) grow(q);
    }
    speed = p.options.move_speed_mm_s;
    const double n = p.pattern == PosePattern::kList ? static_cast<double>(p.poses.size()) : p.count;
    seconds += n * (1.875 * (hi - lo).norm() / speed + p.options.settle.timeout_s + p.options.average_s);
  }
  if (s.path) seconds += path_duration(*s.path) + 1.875 * (hi - lo).norm() / speed;
  const double rows = seconds * rows_per_s;
  if (rows > kMaxLogRows) {
    fail(c.at(s.sampling ? "sampling.count" : "path"), s.sampling ? root["sampling"] : root["path"],
         fmt::format("the run could log up to {:.3g} trajectory rows ({:.3g} s simulated at {} Hz / "
                     "log.every {}), more than the {:.0e} that fit in memory: use fewer poses, "
                     "shorter timeouts, faster moves or a larger log.every",
                     rows, seconds, s.twin.servo_rate_hz, s.log_every, kMaxLogRows));
  }
}

}  // namespace

Path path_from_yaml(const YAML::Node& n, const std::string& file, const std::string& keypath,
                    const PathDefaults& defaults) {
  return parse_path(n, Ctx{file, keypath}, &defaults);
}

namespace {

// True when an effects section is, or starts from, the randomized preset.
bool uses_randomized_preset(const YAML::Node& fx) {
  const YAML::Node p = fx.IsMap() ? fx["preset"] : fx;
  return p && p.IsScalar() && p.Scalar() == "randomized";
}

}  // namespace

// effects: the twin's reading and drive effects (and, for a randomized
// preset, masses drawn within the data sheet's tolerance with the drives
// tuned to them); checked against the robot's transmission.
void parse_twin_effects(const YAML::Node& fx, const std::string& file, Scenario& s) {
  s.twin.effects = parse_effects(fx, file, s.seed, s.controller.data_sheet);
  if (uses_randomized_preset(fx)) {  // the actual masses too lie anywhere in the data sheet's tolerance
    Rng rng(derive_seed(s.seed, Stream::kRandomizedMasses));
    const double armature = s.twin.mjcf.armature_kg_m2;
    draw_masses_within(rng, s.controller.data_sheet, s.twin.mjcf);
    // The drives are tuned to the rotor they turn (a drive's auto-tuning
    // keeps its velocity-loop bandwidth kv / J): kv follows the drawn inertia.
    for (ServoDrive& d : s.twin.drives) d.kv *= s.twin.mjcf.armature_kg_m2 / armature;
  }
  try {
    check_transmission(s.controller, s.twin);
  } catch (const InputError& e) {
    throw InputError(yaml_where(file, fx, "") + e.what());
  }
}

// log: trajectory.csv's rate (kDefaultLogRateHz unless log.every or log.rate_hz
// says otherwise; log.every: 1 is the servo rate) into s.log_every.
void parse_log(const YAML::Node& root, const Ctx& c, Scenario& s) {
  const std::string& file = c.file;
  double log_rate_hz = kDefaultLogRateHz;
  if (const YAML::Node l = root["log"]) {
    yaml_check_keys(l, file, "log", {"every", "rate_hz"});
    if (l["every"] && l["rate_hz"])
      fail(c.at("log"), l, "give log.every or log.rate_hz, not both");
    if (l["every"]) s.log_every = static_cast<int>(yaml_integer(l["every"], file, "log.every", 1, 1000000));
    if (l["rate_hz"]) {
      log_rate_hz = yaml_positive(l["rate_hz"], file, "log.rate_hz");
      if (log_rate_hz > s.twin.servo_rate_hz)
        fail(c.at("log.rate_hz"), l["rate_hz"],
             fmt::format("must be at most the servo rate ({} Hz; log.every: 1 logs every servo period), got {}",
                         s.twin.servo_rate_hz, log_rate_hz));
    }
  }
  if (!root["log"] || !root["log"]["every"])
    s.log_every = std::max(1, static_cast<int>(std::lround(s.twin.servo_rate_hz / log_rate_hz)));
}

// robot: the controller's robot (a map, or a robot file relative to base_dir; default the GPM2002).
Robot parse_robot_section(const YAML::Node& r, const std::string& file, const std::string& base_dir) {
  if (!r) return load_robot(gpm::models_dir() + "/gpm2002.yaml");
  return r.IsMap() ? robot_from_yaml(r, file, "robot") : robot_file_at(r, file, "robot", base_dir);
}

// Fails unless the servo rate divides the physics rate.
void check_servo_divides_physics(const YAML::Node& root, const Ctx& c, const Scenario& s) {
  const double ratio = 1.0 / (s.twin.servo_rate_hz * s.twin.mjcf.timestep_s);
  if (std::abs(ratio - std::round(ratio)) > 1e-9 * ratio || std::round(ratio) < 1.0) {
    const YAML::Node at = root["servo"] && root["servo"]["rate_hz"] ? root["servo"]["rate_hz"] : root;
    fail(c.at("servo.rate_hz"), at,
         fmt::format("{} Hz must divide the physics rate {} Hz (1 / physics.timestep_s)",
                     s.twin.servo_rate_hz, 1.0 / s.twin.mjcf.timestep_s));
  }
}

Scenario scenario_from_yaml(const YAML::Node& root, const std::string& file, const std::string& base_dir) {
  const Ctx c{file, ""};
  if (!root.IsMap()) fail(c, root, "expected a map of sections (see scenarios/SCHEMA.md)");
  yaml_check_keys(root, file, "",
                  {"name", "description", "robot", "seed", "actual", "physics", "servo", "encoder",
                   "sampling", "path", "log", "effects", "operation", "events", "calibration", "compensation", "expect",
                   "hardware", "outputs", "render", "monitor"});
  Scenario s;
  s.file = file;
  s.name = root["name"] ? yaml_string(root["name"], file, "name")
                        : std::filesystem::path(file).stem().string();
  s.controller = parse_robot_section(root["robot"], file, base_dir);
  if (root["seed"]) s.seed = static_cast<std::uint64_t>(yaml_integer(root["seed"], file, "seed", 0, (1LL << 53)));
  if (root["actual"]) s.actual = parse_actual(root["actual"], c.at("actual"), base_dir);
  else s.actual.keep = FreeMask{}.set(kXa1).set(kYa1).set(kXa2).set(kYa2);
  if (const YAML::Node p = root["physics"]) {
    yaml_check_keys(p, file, "physics", {"timestep_s"});
    opt_bounded(p, "timestep_s", c.at("physics"), 1e-5, 2e-3, "s", s.twin.mjcf.timestep_s);
    s.twin.mjcf.solref_timeconst_s = std::max(s.twin.mjcf.solref_timeconst_s, 2.0 * s.twin.mjcf.timestep_s);
  }
  if (root["servo"]) {
    parse_servo(root["servo"], c.at("servo"), s.twin);
    opt_bounded(root["servo"], "max_tracking_mm", c.at("servo"), 0.0, 1000.0, "mm (0: not watched)", s.max_tracking_mm);
  }
  check_servo_divides_physics(root, c, s);
  if (root["encoder"]) parse_encoder(root["encoder"], c.at("encoder"), s.twin.encoder);
  if (const YAML::Node fx = root["effects"]) parse_twin_effects(fx, file, s);
  if (root["sampling"]) s.sampling = parse_sampling(root["sampling"], c.at("sampling"));
  if (root["path"]) s.path = parse_path(root["path"], c.at("path"));
  parse_log(root, c, s);
  if (root["operation"]) s.operation = parse_operation(root["operation"], c.at("operation"));
  if (const YAML::Node ev = root["events"]) {
    if (!s.operation) fail(c.at("events"), ev, "events happen during operation: give an 'operation' section");
    s.twin.events = parse_events(ev, c.at("events"), s.operation->duration_s);
  }
  if (!s.sampling && !s.path && !s.operation)
    fail(c, root, "nothing to simulate: give a 'sampling', 'path' or 'operation' section");
  check_log_size(s, root, c);
  return s;
}

Scenario parse_scenario(const std::string& text, const std::string& file, const std::string& base_dir) {
  return scenario_from_yaml(load_yaml_string(text, file), file, base_dir);
}

Scenario load_scenario(const std::string& path) {
  const std::string base = std::filesystem::path(path).parent_path().string();
  return scenario_from_yaml(load_yaml_file(path), path, base.empty() ? "." : base);
}

Robot make_actual(const Scenario& s) {
  Robot actual = s.controller;
  actual.name = s.controller.name + " (actual)";
  actual.calibration.reset();  // a controller read from a result file: its std etc. are not the actual robot's
  Rng rng(derive_seed(s.seed, Stream::kActualParameters));
  for (int i = 0; i < kNumParams; ++i) {
    const double z = rng.normal();  // drawn for every parameter: streams do not shift
    const auto& ex = s.actual.explicit_values[static_cast<size_t>(i)];
    if (ex) {
      actual.geometry[i] = *ex;
      continue;
    }
    if (s.actual.keep.test(static_cast<size_t>(i))) continue;
    const double sigma = is_offset(i) ? s.actual.sigma_offset_rad
                         : is_length(i) ? s.actual.sigma_link_mm
                                        : s.actual.sigma_base_mm;
    actual.geometry[i] += sigma * z;
  }
  try {
    validate_robot(actual, "actual");
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: actual: the actual parameters cannot assemble: {}", s.file, e.what()));
  }
  return actual;
}

std::vector<Eigen::Vector2d> plan_poses(const SamplingPlan& p, std::uint64_t seed) {
  switch (p.pattern) {
    case PosePattern::kDisc: {
      Rng rng(derive_seed(seed, Stream::kSamplePoses));
      return disc_poses(p.centre, p.radius, p.count, rng);
    }
    case PosePattern::kCircle: return circle_points(p.centre, p.radius, p.count);
    case PosePattern::kLine: return line_points(p.from, p.to, p.count);
    case PosePattern::kList: return p.poses;
    case PosePattern::kDesigned:
    case PosePattern::kTrajectory:
      if (p.poses.empty())
        throw InputError("sampling: designed poses are made by the calibration layer (gpm run, gpm simulate); none were given");
      return p.poses;
  }
  return {};
}

}  // namespace gpm::sim
