#include "hw/procedures/sampling_session.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "hw/procedures/motion.hpp"
#include "hw/hw_errors.hpp"
#include "models/errors.hpp"
#include "models/kinematics.hpp"

namespace gpm::hw {
namespace {

// Encoder-space joint targets of the controller model at p, each taken
// within pi of near (readings wrap at 2 pi).
Eigen::Vector3d ik_readings(const Robot& c, const Eigen::Vector2d& p, const Eigen::Vector3d& near) {
  const JointAngles q = inverse_kinematics(c.geometry, p, c.branch);
  Eigen::Vector3d m = readings_from_active(c.geometry, q.theta_a);
  for (int i = 0; i < 3; ++i) m[i] = near[i] + wrap_pi(m[i] - near[i]);
  return m;
}

// The session on the motion primitive: Cartesian straight moves, settle, average.
class Runner {
 public:
  Runner(SafetySupervisor& hw, const SessionPlan& plan, const std::atomic<bool>* stop, const SampleHook& on_sample)
      : plan_(plan), c_(hw.controller()), motion_(hw, plan.modes, plan.profile_headroom, stop), on_sample_(on_sample) {}

  // Duration of the straight move p0 -> p1 (blending out offset) that keeps
  // every joint within headroom of its velocity and acceleration limits and
  // the Cartesian peak speed at move_speed.
  double move_time(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1, const Eigen::Vector3d& offset) {
    const int n = 40;
    std::vector<Eigen::Vector3d> q(n + 1);
    for (int k = 0; k <= n; ++k) {
      const double s = static_cast<double>(k) / n;
      q[k] = ik_readings(c_, p0 + s * (p1 - p0), motion_.command()) + (1.0 - s) * offset;
    }
    return motion_.path_time(q, std::numbers::pi / 2 * (p1 - p0).norm() / plan_.options.move_speed_mm_s);
  }

  void move(const Eigen::Vector2d& p1) {
    const Eigen::Vector2d p0 = pose_;
    const Eigen::Vector3d offset = motion_.command() - ik_readings(c_, p0, motion_.command());
    const double T = move_time(p0, p1, offset);
    motion_.follow([&](double s) {
      return Eigen::Vector3d(ik_readings(c_, p0 + s * (p1 - p0), motion_.command()) + (1.0 - s) * offset);
    }, T);
    pose_ = p1;
  }

  // Mean readings along the dither figure around p (the robot stands at p),
  // run in average_s or longer, within the limits as the moves are.
  Eigen::Vector3d average_around(const Eigen::Vector2d& p) {
    const Eigen::Vector3d at = motion_.command();
    const auto figure = [&](double s) { return ik_readings(c_, p + dither_offset(s, plan_.dither_mm), at); };
    double T = plan_.options.average_s;
    if (plan_.dither_mm > 0.0) {
      std::vector<Eigen::Vector3d> q;
      for (int k = 0; k <= 40; ++k) q.push_back(figure(k / 40.0));
      T = motion_.path_time(q, T);
    }
    averaged_ = std::max(1L, std::lround(T / motion_.period_s()));  // the cycles average_along reads
    return motion_.average_along([&](double u) { return figure(motion_profile(u)); }, T);
  }

  SessionResult run(SampleLog& log) {
    SessionResult r;
    motion_.start();
    const auto fk = forward_kinematics(c_.geometry, active_from_readings(c_.geometry, motion_.command()));
    if (!fk) throw HardwareError("the controller model has no forward kinematics at the current readings");
    pose_ = fk->p;
    for (size_t k = 0; k < plan_.poses.size(); ++k) {
      const long id = static_cast<long>(k);
      if (log.has(id)) {
        ++r.skipped;
        continue;
      }
      const Eigen::Vector3d reading0 = motion_.state().theta_m, command0 = motion_.command();
      move(plan_.poses[k]);
      motion_.settle(plan_.options.settle, fmt::format("sample {}: ", id), plan_.require_settled);
      if (plan_.check_following) motion_.check_followed(reading0, command0, fmt::format("sample {}: ", id));
      log.append(id, average_around(plan_.poses[k]), plan_.poses[k]);
      if (on_sample_) on_sample_(id, averaged_);
      ++r.taken;
    }
    motion_.finish();
    r.duration_s = motion_.now();
    return r;
  }

 private:
  const SessionPlan& plan_;
  const Robot& c_;
  Motion motion_;
  const SampleHook& on_sample_;
  Eigen::Vector2d pose_ = Eigen::Vector2d::Zero();
  long averaged_ = 1;  // cycles of the last average
};

}  // namespace

Eigen::Vector2d dither_offset(double s, double radius_mm) {
  return radius_mm * Eigen::Vector2d(std::sin(2 * std::numbers::pi * s), 0.5 * std::sin(4 * std::numbers::pi * s));
}

void check_resumed_plan(const Robot& controller, const SessionPlan& plan, const SampleLog& log) {
  for (const auto& [id, row] : log.recorded()) {
    if (id < 0 || id >= static_cast<long>(plan.poses.size())) {
      throw InputError(fmt::format("{}: sample {} is not in this plan of {} poses: the file was "
                                   "recorded with another plan; choose another output file",
                                   log.path(), id, plan.poses.size()));
    }
    const Eigen::Vector2d& p = plan.poses[static_cast<size_t>(id)];
    if (row.has_target && (row.target - p).norm() > 1e-9 * (1.0 + p.norm())) {
      throw InputError(fmt::format("{}: sample {} was taken at ({}, {}) mm but pose {} of this plan is "
                                   "({}, {}) mm: the file was recorded with another plan (poses, "
                                   "order or seed); choose another output file",
                                   log.path(), id, row.target.x(), row.target.y(), id, p.x(), p.y()));
    }
    const Reach reach = check_reach(controller, p);
    if (!reach.ok) continue;  // refused with the pose check
    const Eigen::Vector3d q = readings_from_active(controller.geometry, reach.q.theta_a);
    for (int i = 0; i < 3; ++i) {
      if (plan.modes[i] != JointMode::kPosition) continue;
      const double gap = std::abs(wrap_pi(row.theta_m[i] - q[i]));
      if (gap > kSameRobotRad) {
        throw InputError(fmt::format("{}: sample {} reads joint {} {:.4f} rad away from where this "
                                     "controller model puts pose {} (at most {} rad for the same "
                                     "robot): the file was recorded on another robot or model; "
                                     "choose another output file",
                                     log.path(), id, i + 1, gap, id, kSameRobotRad));
      }
    }
  }
}

void check_plan_poses(const SafetySupervisor& hw, const SessionPlan& plan) {
  if (!(plan.dither_mm >= 0.0 && plan.dither_mm <= 5.0))
    throw InputError(fmt::format("sampling dither {} mm: expected 0 to 5 mm", plan.dither_mm));
  // Every pose, with its dither figure, must be allowed before anything moves.
  for (size_t k = 0; k < plan.poses.size(); ++k) {
    const Robot& c = hw.controller();
    std::string why;
    for (int j = 0; j < 8 && why.empty(); ++j) {
      const Reach reach = check_reach(c, plan.poses[k] + dither_offset(j / 8.0, plan.dither_mm));
      why = reach.ok ? "" : reach.reason;
      if (why.empty()) why = hw.check_pose(readings_from_active(c.geometry, reach.q.theta_a));
    }
    if (!why.empty()) {
      const std::string figure =
          plan.dither_mm > 0.0 ? fmt::format(" with its {} mm dither figure (dither_mm: 0 holds still)", plan.dither_mm)
                               : "";
      throw InputError(fmt::format("pose {} ({}, {}) mm{} is outside the safety limits: {}", k,
                                   plan.poses[k].x(), plan.poses[k].y(), figure, why));
    }
  }
}

HardwareError session_stopped(SafetySupervisor& hw, const std::string& why, const SampleLog& log) {
  hw.emergency_stop(why);
  hw.shutdown();
  const std::string_view tail = ": drives disabled";
  const bool said = why.size() >= tail.size() && why.compare(why.size() - tail.size(), tail.size(), tail) == 0;
  return HardwareError(fmt::format("{}{}; {} samples kept in {}", why, said ? "" : tail, log.size(), log.path()));
}

void rethrow_session_error(SafetySupervisor& hw, const SampleLog& log) {
  try {
    throw;
  } catch (const Interrupted& e) {
    hw.shutdown();
    throw Interrupted(fmt::format("{}; {} samples kept in {}", e.what(), log.size(), log.path()));
  } catch (const CommandRejected& e) {
    throw session_stopped(hw, e.what(), log);
  } catch (const HardwareError& e) {
    throw session_stopped(hw, e.what(), log);
  } catch (const LifecycleError& e) {
    throw session_stopped(hw, e.what(), log);
  }
}

SessionResult run_sampling_session(SafetySupervisor& hw, const SessionPlan& plan, SampleLog& log,
                                   const std::atomic<bool>* stop, const SampleHook& on_sample) {
  check_plan_poses(hw, plan);
  check_resumed_plan(hw.controller(), plan, log);
  Runner runner(hw, plan, stop, on_sample);
  try {
    SessionResult r = runner.run(log);
    hw.shutdown();
    return r;
  } catch (...) {
    rethrow_session_error(hw, log);
  }
}

}  // namespace gpm::hw
