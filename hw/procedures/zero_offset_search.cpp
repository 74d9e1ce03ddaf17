#include "hw/procedures/zero_offset_search.hpp"

#include <chrono>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include <fmt/format.h>

#include "calib/projected_error.hpp"
#include "hw/procedures/motion.hpp"
#include "hw/hw_errors.hpp"
#include "models/bounds.hpp"
#include "models/errors.hpp"
#include "models/kinematics.hpp"

namespace gpm::hw {
namespace {

constexpr double kPi = std::numbers::pi;

// A point refused by the procedure's own check before anything moved there.
class PointRefused : public std::runtime_error {
 public:
  explicit PointRefused(const std::string& what) : std::runtime_error(what) {}
};


std::string fmt_v3(const Eigen::Vector3d& v) {
  return fmt::format("({:.6f}, {:.6f}, {:.6f})", v[0], v[1], v[2]);
}

// Joint modes of the search: the sensor joint read only, the others in position.
std::array<JointMode, 3> sensor_modes(int sensor_joint) {
  std::array<JointMode, 3> m{};
  for (int k = 0; k < 3; ++k) m[k] = k == sensor_joint ? JointMode::kTorqueOff : JointMode::kPosition;
  return m;
}

void validate(const ZeroSearchOptions& o) {  // see validate_zero_search_options
  auto bad = [](const std::string& s) { throw InputError("zero-offset search: " + s); };
  if (!(o.circle_radius_mm > 0)) bad("circle radius must be > 0 mm");
  if (!within(o.circle_points, limits::kCirclePoints))
    bad("interpolation points per circle must be " + describe(limits::kCirclePoints));
  if (!(o.circle_speed_mm_s > 0) || !(o.move_speed_mm_s > 0)) bad("speeds must be > 0 mm/s");
  if (!within(o.circle_dwell_s, limits::kDwell))
    bad("the dwell at each interpolation point must be " + describe(limits::kDwell));
  if (!(o.d_min_mm > 0) || !(o.d_initial_mm >= o.d_min_mm)) bad("need 0 < d_min <= d_initial (mm)");
  const double levels = std::log2(o.d_initial_mm / o.d_min_mm);
  if (std::abs(levels - std::round(levels)) > 1e-9) bad("d_initial / d_min must be a power of 2");
  if (o.sensor_joint < 0 || o.sensor_joint > 2) bad("sensor joint must be 1, 2 or 3");
  if (!(o.profile_headroom > 0 && o.profile_headroom <= 1)) bad("profile headroom must be in (0, 1]");
  if (o.max_rounds < 1 || o.direct_iterations < 1) bad("round and iteration limits must be >= 1");
}

class Runner {
 public:
  Runner(SafetySupervisor& hw, const ZeroSearchOptions& o, const ZeroTraceSink& sink,
         ZeroSearchResult& r, const std::atomic<bool>* stop)
      : hw_(hw), o_(o), sink_(sink), r_(r), c_(hw.controller()),
        motion_(hw, sensor_modes(o.sensor_joint), o.profile_headroom, stop) {
    for (int k = 0; k < 3; ++k) modes_[k] = k == o.sensor_joint ? JointMode::kTorqueOff : JointMode::kPosition;
    for (int k = 0; k < 3; ++k)
      if (k != o.sensor_joint) (pi_ < 0 ? pi_ : pj_) = k;
    const JointAngles home = inverse_kinematics(c_.geometry, c_.home, c_.branch);
    pair_mode_ = assembly_mode(c_.geometry, home.theta_a, c_.home, pi_, pj_);
    ref_angles_ = inverse_kinematics(c_.geometry, o.reference, c_.branch).theta_a;
  }

  std::string where() const { return where_; }
  double now() const { return motion_.now(); }

  // Step 1 (and the start): activate, optionally jog, take R as the first estimate.
  void start() {
    motion_.start();
    if (o_.jog_to_start) {
      where_ = fmt::format("jog to the start ({:.3f}, {:.3f}) mm", o_.start.x(), o_.start.y());
      const Eigen::Vector3d q = readings_from_active(
          c_.geometry, inverse_kinematics(c_.geometry, o_.start, c_.branch).theta_a);
      require_safe(wrap_near(q), "start point");
      move_joints(wrap_near(q));
      settle();
    }
  }

  // Steps 2-4 at the point reached by commanding O + shift with the start's offsets.
  ZeroCandidate evaluate(const Eigen::Vector2d& shift, int round, double d) {
    ZeroCandidate z;
    z.index = static_cast<int>(r_.trace.size());
    z.round = round;
    z.d_mm = d;
    z.shift = shift;
    where_ = fmt::format("estimate {} (round {}, d {} mm) at search point ({:+.4f}, {:+.4f}) mm",
                         z.index, round, d, shift.x(), shift.y());
    if (z.index > 0) {
      const Eigen::Vector3d q = command_for(o_.reference + shift, r_.initial_offsets);
      require_safe(q, "estimate");
      // The circle with the offsets the point will give (predicted: readings = command).
      const Eigen::Vector3d predicted = wrap3(ref_angles_ - q);
      check_circle(predicted);
      move_joints(q);
    }
    settle();
    z.readings = average();
    if (z.index > 0) check_sensor(o_.reference + shift, r_.initial_offsets, z.readings);
    z.offsets = wrap3(ref_angles_ - z.readings);  // step 2: IK(O) - readings(R)
    if (z.index == 0) r_.initial_offsets = z.offsets;
    check_circle(z.offsets);
    track_circle(z.offsets, z);  // step 3
    z.E = calib::projected_error(c_, z.offsets, z.desired, z.circle);  // step 4, eq. 17-19
    finish(z);
    return z;
  }

  // Direct method: track with the given offsets from the point that reads as O.
  ZeroCandidate evaluate_at(const Eigen::Vector3d& dth, int round) {
    ZeroCandidate z;
    z.index = static_cast<int>(r_.trace.size());
    z.round = round;
    const Eigen::Vector3d q = command_for(o_.reference, dth);
    z.shift = frame0_point(q) - o_.reference;
    where_ = fmt::format("direct iteration {} at search point ({:+.4f}, {:+.4f}) mm with offsets {}",
                         round, z.shift.x(), z.shift.y(), fmt_v3(dth));
    require_safe(q, "reference point");
    check_circle(dth);
    move_joints(q);
    settle();
    z.readings = average();
    z.offsets = dth;
    track_circle(dth, z);
    z.E = calib::projected_error(c_, dth, z.desired, z.circle);
    finish(z);
    return z;
  }

  void stop_normally() { motion_.finish(); }

 private:
  void finish(const ZeroCandidate& z) {
    r_.trace.push_back(z);
    if (sink_) sink_(z);
  }

  Eigen::Vector3d wrap_near(const Eigen::Vector3d& q) const { return motion_.wrap_near(q); }
  static Eigen::Vector3d wrap3(const Eigen::Vector3d& v) {
    return Eigen::Vector3d(wrap_pi(v[0]), wrap_pi(v[1]), wrap_pi(v[2]));
  }

  // Encoder-space command of point p with offsets dth: IK(p) - dth (eq. 1).
  Eigen::Vector3d command_for(const Eigen::Vector2d& p, const Eigen::Vector3d& dth) const {
    const JointAngles q = inverse_kinematics(c_.geometry, p, c_.branch);
    return wrap_near(q.theta_a - dth);
  }

  // The point the two commanded joints reach, in the frame of the start's offsets.
  Eigen::Vector2d frame0_point(const Eigen::Vector3d& q) const {
    Geometry g = c_.geometry;
    for (int i = 0; i < 3; ++i) g[dth(i)] = r_.initial_offsets[i];
    const auto p = forward_kinematics_two(g, active_from_readings(g, q), pi_, pj_, pair_mode_);
    return p ? *p : Eigen::Vector2d(NAN, NAN);
  }

  // Why the two commanded joints at q are not allowed as a static pose: the
  // supervisor's pose check (joint limits, workspace disc, reach and
  // singularity margins of its controller model), then this procedure's own
  // guard on the driven pair; empty when allowed.
  std::string why_unsafe(const Eigen::Vector3d& q) const {
    const std::string why = hw_.check_pose(q, modes_);
    if (!why.empty()) return why;
    const auto p = forward_kinematics_two(c_.geometry, active_from_readings(c_.geometry, q), pi_,
                                          pj_, pair_mode_);
    if (!p) return fmt::format("passive links {} and {} cannot meet", pi_ + 1, pj_ + 1);
    const Reach reach = check_reach(c_, *p);
    if (!reach.ok) return fmt::format("({:.3f}, {:.3f}) mm: {}", p->x(), p->y(), reach.reason);
    // Only two chains are driven: their passive links must cross well (the
    // mechanism is held by them alone; the free chain follows).
    const double s = std::abs(std::sin(reach.q.theta_b[pi_] - reach.q.theta_b[pj_]));
    if (s < o_.min_pair_sine) {
      return fmt::format("({:.3f}, {:.3f}) mm: the driven chains {} and {} are near their pair "
                         "singularity (|sin| of the passive-link angle {:.3f} < {})",
                         p->x(), p->y(), pi_ + 1, pj_ + 1, s, o_.min_pair_sine);
    }
    return {};
  }

  // The read-only joint must read near where the driven joints put it (its
  // offset error is small): a large gap means its free chain changed branch.
  void check_sensor(const Eigen::Vector2d& p, const Eigen::Vector3d& dth, const Eigen::Vector3d& reading) const {
    const int k = o_.sensor_joint;
    const double expected = inverse_kinematics(c_.geometry, p, c_.branch).theta_a[k] - dth[k];
    const double gap = std::abs(wrap_pi(reading[k] - expected));
    if (gap > o_.max_sensor_gap_rad) {
      throw HardwareError(fmt::format("joint {} (read only) reads {:.4f} rad away from where the "
                                      "driven joints put it (max {} rad): its chain may have "
                                      "changed assembly branch",
                                      k + 1, gap, o_.max_sensor_gap_rad));
    }
  }

  void require_safe(const Eigen::Vector3d& q, const char* what) const {
    const std::string why = why_unsafe(q);
    if (!why.empty()) throw PointRefused(fmt::format("{} outside the safe workspace: {}", what, why));
  }

  std::vector<Eigen::Vector2d> circle_points(int n) const {
    std::vector<Eigen::Vector2d> out;
    for (int k = 0; k < n; ++k) {
      const double a = 2 * kPi * k / n;
      out.push_back(o_.reference + o_.circle_radius_mm * Eigen::Vector2d(std::cos(a), std::sin(a)));
    }
    return out;
  }

  void check_circle(const Eigen::Vector3d& dth) const {
    for (const Eigen::Vector2d& p : circle_points(72)) {
      const Reach reach = check_reach(c_, p);
      if (!reach.ok) {
        throw PointRefused(fmt::format("circle point ({:.3f}, {:.3f}) mm is out of reach: {}",
                                       p.x(), p.y(), reach.reason));
      }
      const std::string why = why_unsafe(wrap_near(reach.q.theta_a - dth));
      if (!why.empty()) {
        throw PointRefused(fmt::format("circle point ({:.3f}, {:.3f}) mm with offsets {} is outside "
                                       "the safe workspace: {}",
                                       p.x(), p.y(), fmt_v3(dth), why));
      }
    }
  }

  void cycle(const Eigen::Vector3d& q) { motion_.cycle(q); }
  double path_time(const std::vector<Eigen::Vector3d>& q, double min_T) const {
    return motion_.path_time(q, min_T);
  }
  void move_joints(const Eigen::Vector3d& q1) {
    motion_.move_joints(q1, o_.move_speed_mm_s);
    ++r_.motions;
  }
  void settle() {
    motion_.settle({o_.settle_velocity_rad_s, o_.settle_hold_s, o_.settle_timeout_s}, "");
  }
  Eigen::Vector3d average() { return motion_.average(o_.average_s); }

  // Step 3: out to the circle, once round it (cosine time law on the angle),
  // recording the reading one cycle after each interpolation point is commanded.
  void track_circle(const Eigen::Vector3d& dth, ZeroCandidate& z) {
    const double rad = o_.circle_radius_mm;
    auto point = [&](double s) {
      const double a = 2 * kPi * s;
      return Eigen::Vector2d(o_.reference + rad * Eigen::Vector2d(std::cos(a), std::sin(a)));
    };
    move_joints(command_for(point(0.0), dth));
    if (o_.circle_dwell_s > 0) {
      track_circle_stopping(dth, z, point);
      return;
    }
    std::vector<Eigen::Vector3d> path;
    for (int k = 0; k <= 96; ++k) path.push_back(command_for(point(k / 96.0), dth));
    // Peak tangential speed of the cosine law: 2 pi r * pi / (2 T).
    const double T = path_time(path, kPi * kPi * rad / o_.circle_speed_mm_s);
    const long steps = static_cast<long>(std::ceil(T / motion_.period_s()));
    const int n = o_.circle_points;
    std::vector<long> at(n);
    for (int j = 0; j < n; ++j) at[j] = std::lround(steps * std::acos(1.0 - 2.0 * j / n) / kPi);
    int next = 0;
    bool pending = false;
    for (long k = 0; k <= steps + 1; ++k) {
      const double s = motion_profile(static_cast<double>(std::min(k, steps)) / steps);
      const Eigen::Vector2d p = point(s);
      const Eigen::Vector3d q = k == 0 ? motion_.command() : command_for(p, dth);
      cycle(q);
      if (pending) {  // the reading after the interpolation point's command
        check_sensor(z.desired.back(), dth, motion_.state().theta_m);
        z.circle.push_back(motion_.state().theta_m);
        pending = false;
      }
      if (next < n && k == at[next]) {
        z.desired.push_back(p);
        pending = true;
        ++next;
      }
    }
    ++r_.motions;
    ++r_.circles;
  }

  // Step 3 stop and go: arc to each interpolation point, settle, average the
  // readings over circle_dwell_s (less noise and no lag, more time).
  template <class Point>
  void track_circle_stopping(const Eigen::Vector3d& dth, ZeroCandidate& z, const Point& point) {
    const int n = o_.circle_points;
    for (int j = 0; j <= n; ++j) {
      if (j > 0) {
        const double s0 = static_cast<double>(j - 1) / n, s1 = static_cast<double>(j) / n;
        std::vector<Eigen::Vector3d> path;
        for (int k = 0; k <= 8; ++k) path.push_back(command_for(point(s0 + (s1 - s0) * k / 8.0), dth));
        const double arc = 2 * kPi * o_.circle_radius_mm / n;
        const double T = path_time(path, kPi / 2 * arc / o_.circle_speed_mm_s);
        motion_.follow([&](double u) { return command_for(point(s0 + (s1 - s0) * u), dth); }, T);
      }
      if (j == n) break;  // back at the start: already recorded
      settle();
      const Eigen::Vector3d mean = motion_.average(o_.circle_dwell_s);
      check_sensor(point(static_cast<double>(j) / n), dth, mean);
      z.desired.push_back(point(static_cast<double>(j) / n));
      z.circle.push_back(mean);
    }
    ++r_.motions;
    ++r_.circles;
  }

  SafetySupervisor& hw_;
  const ZeroSearchOptions& o_;
  const ZeroTraceSink& sink_;
  ZeroSearchResult& r_;
  const Robot& c_;
  Motion motion_;
  std::array<JointMode, 3> modes_{};
  int pi_ = -1, pj_ = -1, pair_mode_ = 1;
  Eigen::Vector3d ref_angles_ = Eigen::Vector3d::Zero();
  std::string where_ = "start";
};

// Steps 5-7: the 9-point pattern, recentring on the smallest E, halving d.
void run_grid(Runner& run, const ZeroSearchOptions& o, ZeroSearchResult& r) {
  const double quantum = o.d_min_mm;
  std::map<std::pair<long, long>, ZeroCandidate> seen;  // each point evaluated once
  auto key = [&](const Eigen::Vector2d& s) {
    return std::make_pair(std::lround(s.x() / quantum), std::lround(s.y() / quantum));
  };
  double d = o.d_initial_mm;
  ZeroCandidate centre = run.evaluate(Eigen::Vector2d::Zero(), 0, d);
  seen.emplace(key(centre.shift), centre);
  // Step 5 order: +x, +x+y, +y, -x+y, -x, -x-y, -y, +x-y.
  const int dirs[8][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}};
  for (int round = 1;; ++round) {
    if (round > o.max_rounds) {
      throw HardwareError(fmt::format("the pattern search did not finish within {} rounds",
                                      o.max_rounds));
    }
    ZeroCandidate best = centre;
    for (const auto& dd : dirs) {
      const Eigen::Vector2d s = centre.shift + d * Eigen::Vector2d(dd[0], dd[1]);
      auto it = seen.find(key(s));
      if (it == seen.end()) it = seen.emplace(key(s), run.evaluate(s, round, d)).first;
      if (it->second.E < best.E) best = it->second;
    }
    if (best.index != centre.index) {  // step 6: recentre, same d
      centre = best;
      continue;
    }
    if (d <= o.d_min_mm * (1 + 1e-9)) break;  // step 7
    d /= 2;
  }
  r.offsets = centre.offsets;
  r.shift = centre.shift;
  r.E = centre.E;
  r.d_final_mm = d;
}

// Fit the offsets from each circle (E quadratic in dth), track again with them.
void run_direct(Runner& run, const ZeroSearchOptions& o, const Robot& c, ZeroSearchResult& r) {
  ZeroCandidate z = run.evaluate(Eigen::Vector2d::Zero(), 0, 0.0);
  Eigen::Vector3d dth = calib::minimise_projected_error(c, z.desired, z.circle);
  for (int it = 1; it < o.direct_iterations; ++it) {
    z = run.evaluate_at(dth, it);
    const Eigen::Vector3d next = calib::minimise_projected_error(c, z.desired, z.circle);
    const double change = (next - dth).cwiseAbs().maxCoeff();
    dth = next;
    if (change < o.direct_tolerance_rad) break;
  }
  r.offsets = dth;
  r.shift = z.shift;
  r.E = calib::projected_error(c, dth, z.desired, z.circle);
}

}  // namespace

void validate_zero_search_options(const ZeroSearchOptions& options) { validate(options); }

const char* zero_method_name(ZeroMethod m) { return m == ZeroMethod::kGrid ? "grid" : "direct"; }

ZeroSearchStopped::ZeroSearchStopped(const std::string& what, ZeroSearchResult partial, bool interrupted)
    : HardwareError(what), partial_(std::move(partial)), interrupted_(interrupted) {}

ZeroSearchResult run_zero_offset_search(SafetySupervisor& hw, const ZeroSearchOptions& options,
                                        const ZeroTraceSink& sink, const std::atomic<bool>* stop) {
  validate(options);
  {
    const Reach reach = check_reach(hw.controller(), options.reference);
    if (!reach.ok) throw InputError("zero-offset search: the reference point is out of reach: " + reach.reason);
  }
  ZeroSearchResult r;
  r.method = options.method;
  const auto wall0 = std::chrono::steady_clock::now();
  Runner run(hw, options, sink, r, stop);
  auto times = [&] {
    r.robot_time_s = run.now();
    r.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  };
  // Stops the robot (normally before a motion, by emergency stop during one),
  // and throws what the caller gets: the reason and what was done so far.
  auto fail = [&](const std::string& what, bool moving, bool interrupted) {
    r.ok = false;
    r.error = fmt::format("{}: {}", run.where(), what);
    if (moving) {
      hw.emergency_stop(r.error);
    } else {
      try {
        run.stop_normally();
      } catch (...) {
        hw.emergency_stop(r.error);
      }
    }
    hw.shutdown();
    times();
    throw ZeroSearchStopped(r.error, r, interrupted);
  };
  try {
    run.start();
    if (options.method == ZeroMethod::kGrid) run_grid(run, options, r);
    else run_direct(run, options, hw.controller(), r);
    run.stop_normally();
    hw.shutdown();
    r.ok = true;
  } catch (const PointRefused& e) {
    fail(std::string(e.what()) + "; stopped before moving there, drives disabled", false, false);
  } catch (const Interrupted& e) {
    fail(e.what(), true, true);
  } catch (const HardwareError& e) {  // also CommandRejected, SafetyError
    fail(std::string(e.what()) + "; drives disabled", true, false);
  } catch (const LifecycleError& e) {
    fail(std::string(e.what()) + "; drives disabled", true, false);
  } catch (const ReachError& e) {
    fail(std::string(e.what()) + "; drives disabled", true, false);
  }
  times();
  return r;
}

}  // namespace gpm::hw
