// A calibration sampling session on the fly on any RobotHardware (twin,
// drives or a plugin, chosen by config only): the robot moves to the start of
// a continuous excitation path (sim/waypoint_path.hpp, planned by
// sim::excitation_plan with its margin from losing control), follows it at
// the drive loop rate (IK of the controller model, never the twin's actual
// parameters) and every `every`-th cycle becomes one sample: the three
// readings of that cycle with their read times, the drive torques read with
// them, the torque of the cycle before and the mean since the sample before
// (the same record as the twin's sim::sample_along). Samples are appended to
// the log as they are taken; a failure stops the robot and keeps them.
#pragma once

#include <array>
#include <atomic>

#include "hw/hardware_types.hpp"
#include "hw/procedures/sample_log.hpp"
#include "hw/procedures/sampling_session.hpp"
#include "hw/safety_supervisor.hpp"
#include "sim/waypoint_path.hpp"

namespace gpm::hw {

// What to follow and how (constant).
struct TrajectoryPlan {
  sim::WaypointPath path;  // mm, s; starts at rest
  std::array<JointMode, 3> modes{JointMode::kPosition, JointMode::kPosition, JointMode::kPosition};
  int every = 1;                   // one sample every this many cycles (>= 1)
  double move_speed_mm_s = 50.0;   // peak speed of the move to the path's start
  sim::SettleCriterion settle;     // rest before the path starts
  double profile_headroom = 0.5;   // fraction of the limits the move to the start uses
  // Beyond this fraction of the tracking watch's bound (the supervisor's
  // limits().max_tracking_mm, measured at each sample) the path ends early:
  // sampling stops, the robot slows to rest along the path over stop_s and
  // retraces it to its start (0: never; the watch itself disables the drives
  // at its bound).
  double retreat_fraction = 0.7;
  double stop_s = 0.1;
  // > 0: only the path's first end_s seconds are sampled, then the robot
  // slows and retraces them to the start as at an early end, and the session
  // ends normally (a planned first stage, e.g. one that fixes the encoder
  // offsets before the whole path); 0: the whole path.
  double end_s = 0.0;
};

// The encoder-space command of every cycle of plan's path at period_s (IK of
// controller, each reading taken within pi of the one before). Throws
// InputError naming the time and point where the path leaves the
// controller's reach.
std::vector<Eigen::Vector3d> trajectory_commands(const Robot& controller, const TrajectoryPlan& plan,
                                                 double period_s);

// Throws InputError (naming the cycle's time and the reason) unless every
// command of the path passes hw.check_path for plan.modes (poses, speeds,
// accelerations) and every <= 0; nothing moves.
void check_trajectory_plan(const SafetySupervisor& hw, const TrajectoryPlan& plan);

// Runs plan on hw (configured or not; left finalized); samples go to log (a
// log of SampleColumns::kOnTheFly) as they are taken, ids from 0, flushed to
// disk every few cycles and at the end. A log that already holds every
// sample of the path (resume of a finished session) moves nothing; one that
// holds some is refused (a path sampled on the fly is one motion). Errors as
// run_sampling_session (hw/procedures/sampling_session.hpp): InputError
// before anything moves, HardwareError with drives disabled and samples
// kept, Interrupted on a stop request. on_sample (optional): called as each
// sample is logged (hw/procedures/sampling_session.hpp SampleHook). A path
// that ends early (TrajectoryPlan::retreat_fraction) is a PathEndedEarly
// (hw/hw_errors.hpp), raised once the robot is back at the path's start with its drives
// disabled normally (samples kept).
SessionResult run_trajectory_session(SafetySupervisor& hw, const TrajectoryPlan& plan, SampleLog& log,
                                     const std::atomic<bool>* stop = nullptr, const SampleHook& on_sample = {});

// Number of samples run_trajectory_session takes of plan at period_s (up to plan.end_s).
long trajectory_sample_count(const TrajectoryPlan& plan, double period_s);

}  // namespace gpm::hw
