// A calibration sampling session on any RobotHardware (twin or drives,
// chosen by config only): for each pose not yet in the samples file, move
// along a straight line with a smooth profile inside the velocity and
// acceleration limits (IK of the controller model, never the twin's actual
// parameters), wait until the joints settle, average the readings along a
// small closed figure around the pose (dither: the encoders cross many
// counts, so their rounding averages out), append the sample to disk. Any failure stops the robot and keeps what was recorded.
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "hw/hardware_types.hpp"
#include "hw/hw_errors.hpp"
#include "hw/safety_limits.hpp"
#include "hw/safety_supervisor.hpp"
#include "hw/procedures/sample_log.hpp"
#include "models/robot.hpp"
#include "sim/sampling.hpp"

namespace gpm::hw {

// Default size of the dither figure (mm): 0.25 mm at a 244 mm link is about
// 1e-3 rad, some 20 counts of a 17-bit encoder, while the figure's own
// curvature is subtracted exactly (Motion::average_along).
inline constexpr double kDitherMm = 0.25;

// Offset (mm) of the dither figure at s in [0, 1]: a figure of eight
// radius * (sin 2 pi s, sin(4 pi s) / 2). Run with s = motion_profile(t / T)
// it starts and ends at rest at 0 and its time average is 0.
Eigen::Vector2d dither_offset(double s, double radius_mm);

// What to sample and how (constant).
struct SessionPlan {
  std::vector<Eigen::Vector2d> poses;  // mm; sample k is poses[k]
  sim::SamplingOptions options;        // move speed, settle criterion, averaging window
  std::array<JointMode, 3> modes{JointMode::kPosition, JointMode::kPosition, JointMode::kPosition};
  double profile_headroom = 0.5;       // fraction of the velocity/acceleration limits the moves use
  double dither_mm = kDitherMm;        // size of the figure averaged along at each pose (0: hold still);
                                       // averaging lasts options.average_s, longer if the limits need it
  // A pose whose joints do not settle within options.settle.timeout_s fails
  // the session (HardwareError); false: it is sampled as it stands (the
  // scenario's settle criterion: gpm run).
  bool require_settled = true;
  // Each move checked by Motion::check_followed (a drive that does not move,
  // readings that do not change); false: not judged (the in-process twin,
  // whose drives may rightly not follow when they fight over a wrong model;
  // the check changes no sample).
  bool check_following = true;
};

// What a session did.
struct SessionResult {
  long taken = 0;    // samples recorded by this run
  long skipped = 0;  // already in the file (resume)
  double duration_s = 0.0;  // session time (simulated or wall)
};

// Called as sample id is logged, at the cycle of its last reading; the
// sample stands for the readings of its last `cycles` cycles (1 on the fly,
// the averaging window at rest). A simulation takes the twin's truth with it.
using SampleHook = std::function<void(long id, long cycles)>;

// Largest gap (rad) between a recorded reading and the controller model's IK
// of its pose for a file to count as recorded on the same robot (offsets and
// geometry errors are a few 0.01 rad; another robot or model is far beyond).
inline constexpr double kSameRobotRad = 0.1;

// Throws InputError (naming the file and the sample) unless every row already
// in log belongs to plan: its id is a pose of the plan, its target is that
// pose (same poses in the same order) and its readings are within
// kSameRobotRad of the controller's IK there (same robot). Nothing moves.
void check_resumed_plan(const Robot& controller, const SessionPlan& plan, const SampleLog& log);

// Throws InputError (naming the pose and the limit) unless every pose of
// plan, with its dither figure, is reachable and passes hw.check_pose, and
// for a dither outside [0, 5] mm. Nothing moves: a command that runs sessions
// later checks their plans with this before its first motion.
void check_plan_poses(const SafetySupervisor& hw, const SessionPlan& plan);

// A session stopped on why: hw's drives disabled (emergency stop, then
// shutdown) and the error to throw, one line saying so once and where the
// samples taken so far are.
HardwareError session_stopped(SafetySupervisor& hw, const std::string& why, const SampleLog& log);

// Called in a catch block of a session's motion: rethrows what is being
// handled as the session ends on it. Interrupted: hw shut down, the message
// naming where the samples are kept; CommandRejected, HardwareError,
// LifecycleError: session_stopped; anything else as it is.
[[noreturn]] void rethrow_session_error(SafetySupervisor& hw, const SampleLog& log);

// Runs the plan on hw (configured or not; left finalized). Samples go to log
// as they are taken. stop (optional; StopOnSignal::flag) requests a stop.
// Procedure convention (hw/README.md): returns what it did when it finished;
// throws InputError before anything moves for a pose outside the limits
// (check_plan_poses) or a recorded file of another plan (check_resumed_plan),
// HardwareError (drives disabled, samples so far on disk, the message says how
// many and where) on a failure (a position joint whose reading did not follow
// a move is one: Motion::check_followed), Interrupted (a HardwareError) on a
// stop request. on_sample (optional): see SampleHook.
SessionResult run_sampling_session(SafetySupervisor& hw, const SessionPlan& plan, SampleLog& log,
                                   const std::atomic<bool>* stop = nullptr, const SampleHook& on_sample = {});

}  // namespace gpm::hw
