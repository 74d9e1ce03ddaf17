#include "sim/simulate.hpp"

#include <bit>
#include <filesystem>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <unordered_map>
#include <unistd.h>

#include <fmt/format.h>

#include "models/drive_margin.hpp"
#include "models/errors.hpp"
#include "models/rng.hpp"
#include "models/kinematics.hpp"
#include "models/output_file.hpp"
#include "models/robot_yaml.hpp"
#include "models/yaml_util.hpp"
#include "sim/effects.hpp"
#include "sim/moving_sampling.hpp"

namespace gpm::sim {
namespace {

namespace fs = std::filesystem;

std::string x(double v) { return format_exact(v); }

void check_point(const Robot& controller, const Robot& actual, const Eigen::Vector2d& p,
                 const std::string& what) {
  const Reach rc = check_reach(controller, p);
  if (!rc.ok) throw InputError(fmt::format("{}: {}", what, rc.reason));
  const Reach ra = check_reach(actual, p);
  if (!ra.ok) throw InputError(fmt::format("{} on the actual mechanism: {}", what, ra.reason));
}

// What the controller's robot alone says of a point of an excitation path:
// check_reach's and margin_violation's (made only once asked: the point
// must also reach on the actual mechanism).
struct ControllerVerdict {
  bool reaches = false;
  std::string reach;  // check_reach's reason when it does not
  std::optional<std::string> margin;
};

// The verdicts of this thread's last controller, drives and margin, by the
// point's exact coordinates. A study's robots share the controller and the
// designed poses (run/sampling_design.cpp): their excitation paths check
// the same points, and both checks are pure functions of these inputs.
class VerdictMemo {
 public:
  // The verdict at p of controller with drives and margin (made at first use).
  ControllerVerdict& at(const Robot& controller, const DriveMask& drives, const PathMargin& margin,
                        const Eigen::Vector2d& p) {
    if (!(controller_ == controller && drives_ == drives && margin_ == margin) || verdicts_.size() > kMaxPoints) {
      controller_ = controller, drives_ = drives, margin_ = margin;
      verdicts_.clear();
    }
    const Key key{std::bit_cast<std::uint64_t>(p.x()), std::bit_cast<std::uint64_t>(p.y())};
    auto [it, fresh] = verdicts_.try_emplace(key);
    if (fresh) {
      const Reach r = check_reach(controller, p);
      it->second.reaches = r.ok;
      it->second.reach = r.reason;
    }
    return it->second;
  }

 private:
  static constexpr std::size_t kMaxPoints = 1 << 16;  // some ten paths' points; then the memo starts again
  using Key = std::pair<std::uint64_t, std::uint64_t>;
  struct Hash {
    std::size_t operator()(const Key& k) const { return std::hash<std::uint64_t>()(k.first * 0x9E3779B97F4A7C15ULL ^ k.second); }
  };
  Robot controller_;
  DriveMask drives_{};
  PathMargin margin_;
  std::unordered_map<Key, ControllerVerdict, Hash> verdicts_;
};

std::vector<Eigen::Vector2d> path_points(const Path& path) {
  std::vector<Eigen::Vector2d> out;
  const int n = 200;
  for (int k = 0; k <= n; ++k) out.push_back(path_at(path, path_duration(path) * k / n).p);
  return out;
}

}  // namespace

void check_poses_reach(const Scenario& s, const Robot& actual, const std::vector<Eigen::Vector2d>& poses,
                       const std::string& key) {
  for (size_t k = 0; k < poses.size(); ++k) {
    check_point(s.controller, actual, poses[k],
                fmt::format("{}: {}: pose {} ({:.4f}, {:.4f})", s.file, key, k, poses[k].x(), poses[k].y()));
  }
}

void check_path_reach(const Scenario& s, const Robot& actual, const Path& path, const std::string& key) {
  const auto pts = path_points(path);
  for (size_t k = 0; k < pts.size(); ++k) {
    check_point(s.controller, actual, pts[k],
                fmt::format("{}: {}: point at t = {:.3f} s ({:.4f}, {:.4f})", s.file, key,
                            path_duration(path) * static_cast<double>(k) / (pts.size() - 1), pts[k].x(), pts[k].y()));
  }
}

void check_targets(const Scenario& s, const Robot& actual, const std::vector<Eigen::Vector2d>& poses) {
  check_poses_reach(s, actual, poses, "sampling");
  if (s.path) check_path_reach(s, actual, *s.path, "path");
}

DriveMask position_drives(const Scenario& s) {
  DriveMask m{};
  for (std::size_t i = 0; i < m.size(); ++i) m[i] = s.twin.drives[i].mode == ServoMode::kPosition;
  return m;
}

WaypointPath excitation_plan(const Scenario& s, const std::vector<Eigen::Vector2d>& poses,
                             PathRepair* repair) {
  if (!s.sampling || s.sampling->pattern != PosePattern::kTrajectory || poses.empty())
    throw std::logic_error("excitation_plan: not a trajectory plan");
  const DriveMask drives = position_drives(s);
  const PathMargin& margin = s.sampling->margin;
  // Every point: the robot's limits on the controller's model (check_reach),
  // and the margin from losing control for the drives in position mode,
  // widened by the model's tolerance (the verdicts from this thread's memo:
  // the same strings as made afresh).
  thread_local VerdictMemo memo;
  const PointCheck check = [&](const Eigen::Vector2d& p) -> std::string {
    ControllerVerdict& v = memo.at(s.controller, drives, margin, p);
    if (!v.reaches) return v.reach;
    if (!v.margin) v.margin = margin_violation(s.controller, p, drives, margin);
    return *v.margin;
  };
  try {
    return excitation_path(s.controller.home, poses, s.sampling->path_limits, check, repair);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: sampling: excitation path refused before anything moves: {} (sampling.path_margin: "
                                 "singularity {:.3g}, reach_mm {:.3g}, deviation_mm {:.3g})",
                                 s.file, e.what(), margin.singularity, margin.reach_mm, margin.deviation_mm));
  }
}

SimulationResult run_simulation(const Scenario& s, std::function<void(const LogRow&)> sink, Progress* progress) {
  SimulationResult r;
  r.actual = make_actual(s);
  if (s.twin.effects.thermal.on()) r.log.thermal_reference = r.actual.geometry;
  if (sink) r.log.keep_rows = false;
  if (progress && progress->active()) {
    r.log.sink = [sink = std::move(sink), progress](const LogRow& row) {
      if (sink) sink(row);
      progress->update(row.t);
    };
  } else {
    r.log.sink = std::move(sink);
  }
  const std::vector<Eigen::Vector2d> poses =
      s.sampling ? plan_poses(*s.sampling, s.seed) : std::vector<Eigen::Vector2d>{};
  check_targets(s, r.actual, poses);
  const bool in_motion = s.sampling && s.sampling->pattern == PosePattern::kTrajectory;
  // Planned and checked before anything moves.
  const std::optional<WaypointPath> path =
      in_motion ? std::optional<WaypointPath>(excitation_plan(s, poses)) : std::nullopt;
  const TwinModel model(r.actual, s.twin);
  r.model_xml = model.xml();
  TwinState state(model, derive_seed(s.seed, Stream::kTwinNoise));
  r.log.every = s.log_every;
  Session session = make_session(model, state, s.controller, &r.log);
  session.max_tracking_mm = s.max_tracking_mm;
  // On the fly the time of each reading is its id x the sample interval, as
  // the calibration computes the rates (run/calibration_procedure.hpp).
  const auto stamp = [&](std::vector<SampleRecord>& samples) {
    if (!path) return;
    const double dt = s.sampling->sample_every / s.twin.servo_rate_hz;
    for (SampleRecord& rec : samples) rec.t_s = static_cast<double>(rec.id) * dt;
  };
  try {
    if (path) {
      r.samples = sample_along(session, *path, s.sampling->sample_every, 0);
      stamp(r.samples);
    } else {
      for (size_t k = 0; k < poses.size(); ++k)
        r.samples.push_back(take_sample(session, poses[k], static_cast<long>(k), s.sampling->options));
    }
    r.sampling_s = state.data->time;
    if (s.path) {
      const double speed = s.sampling ? s.sampling->options.move_speed_mm_s : 100.0;
      follow_path(session, make_move(session.desired, path_at(*s.path, 0.0).p, speed));
      follow_path(session, *s.path);
    }
  } catch (TrackingStop& stop) {  // what was measured is kept
    if (stop.samples.empty()) stop.samples = std::move(r.samples);
    else stamp(stop.samples);  // taken on the fly before the stop
    stop.rows = std::move(r.log.rows);
    r.log.sink = nullptr;
    if (progress) progress->finish();
    throw;
  }
  r.max_violation_m = r.log.max_violation_m;
  r.max_torque = r.log.max_torque;
  r.log.sink = nullptr;
  if (progress) progress->finish();
  r.simulated_s = state.data->time;
  return r;
}

std::string samples_csv(const std::vector<SampleRecord>& samples) {
  std::string out =
      "sample,theta_m1,theta_m2,theta_m3,x,y,theta_a1,theta_a2,theta_a3,target_x,target_y,settled,tau1,tau2,tau3,"
      "omega1,omega2,omega3,tau_last1,tau_last2,tau_last3,tau_between1,tau_between2,tau_between3,t\n";
  for (const SampleRecord& s : samples) {
    out += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", s.id, x(s.theta_m[0]), x(s.theta_m[1]),
                       x(s.theta_m[2]), x(s.xy_mm.x()), x(s.xy_mm.y()), x(s.theta_a[0]),
                       x(s.theta_a[1]), x(s.theta_a[2]), x(s.target.x()), x(s.target.y()),
                       s.settled ? 1 : 0, x(s.tau[0]), x(s.tau[1]), x(s.tau[2]), x(s.omega[0]), x(s.omega[1]),
                       x(s.omega[2]), x(s.tau_last[0]), x(s.tau_last[1]), x(s.tau_last[2]), x(s.tau_between[0]),
                       x(s.tau_between[1]), x(s.tau_between[2]), x(s.t_s));
  }
  return out;
}

std::string trajectory_header(bool thermal) {
  std::string h = "t,x_des,y_des,x,y,theta_m1,theta_m2,theta_m3,tau1,tau2,tau3,violation_m";
  if (thermal) {
    h += ",growth";
    for (int i = 0; i < kNumParams; ++i)
      if (!is_offset(i)) h += fmt::format(",{}", param_name(i));
  }
  return h + "\n";
}

std::string trajectory_line(const LogRow& r, const Geometry* thermal_reference) {
  std::string out = fmt::format("{},{},{},{},{},{},{},{},{},{},{},{}", x(r.t), x(r.desired.x()),
                                x(r.desired.y()), x(r.actual.x()), x(r.actual.y()), x(r.readings[0]),
                                x(r.readings[1]), x(r.readings[2]), x(r.torque[0]), x(r.torque[1]),
                                x(r.torque[2]), x(r.violation_m));
  if (thermal_reference) {
    const Geometry g = thermal_geometry(*thermal_reference, r.growth, r.growth_base);
    out += fmt::format(",{}", x(r.growth));  // (fmt: GCC 12 warns wrongly on "," + std::string)
    for (int i = 0; i < kNumParams; ++i)
      if (!is_offset(i)) out += fmt::format(",{}", x(g[i]));
  }
  return out + "\n";
}

std::string trajectory_csv(const TrajectoryLog& log) {
  const Geometry* ref = log.thermal_reference ? &*log.thermal_reference : nullptr;
  std::string out = trajectory_header(ref != nullptr);
  for (const LogRow& r : log.rows) out += trajectory_line(r, ref);
  return out;
}

const std::vector<std::string>& simulation_output_names() {
  static const std::vector<std::string> names{"samples.csv", "trajectory.csv", "actual.yaml", "model.xml"};
  return names;
}

void write_simulation(const SimulationResult& r, const std::string& dir) {
  OutputFolder out(dir);  // models/output_file.hpp: all files or none
  out.add("samples.csv", samples_csv(r.samples));
  out.add("trajectory.csv", trajectory_csv(r.log));
  out.add("actual.yaml", robot_to_yaml(r.actual));
  out.add("model.xml", r.model_xml);
  out.commit();
}

SimulationResult simulate_to_folder(const Scenario& s, const std::string& dir, Progress* progress) {
  OutputFolder folder(dir);  // models/output_file.hpp: all files or none
  const std::string traj = folder.staged_path("trajectory.csv");
  std::ofstream out(traj, std::ios::binary | std::ios::trunc);
  const bool thermal = s.twin.effects.thermal.on();
  std::optional<Geometry> ref;
  if (thermal) ref = make_actual(s).geometry;
  out << trajectory_header(thermal);
  SimulationResult r;
  try {
    r = run_simulation(
        s, [&](const LogRow& row) { out << trajectory_line(row, ref ? &*ref : nullptr); }, progress);
  } catch (const TrackingStop& stop) {  // the robot was stopped: what it measured is kept
    out.close();
    folder.add("samples.csv", samples_csv(stop.samples));
    folder.add("actual.yaml", robot_to_yaml(make_actual(s)));
    folder.commit();
    throw;
  }
  out.flush();
  if (!out) throw InputError(fmt::format("{}/trajectory.csv: cannot write file (disk full or not writable?)", dir));
  out.close();
  folder.add("samples.csv", samples_csv(r.samples));
  folder.add("actual.yaml", robot_to_yaml(r.actual));
  folder.add("model.xml", r.model_xml);
  folder.commit();
  return r;
}

}  // namespace gpm::sim
