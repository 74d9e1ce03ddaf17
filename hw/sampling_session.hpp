// A calibration sampling session on any RobotHardware (twin or drives,
// chosen by config only): for each pose not yet in the samples file, move
// along a straight line with a smooth profile inside the velocity and
// acceleration limits (IK of the controller model, never the twin's actual
// parameters), wait until the joints settle, average the readings, append
// the sample to disk. Any failure stops the robot and keeps what was recorded.
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "hw/hardware_types.hpp"
#include "hw/safety_limits.hpp"
#include "hw/safety_supervisor.hpp"
#include "hw/sample_log.hpp"
#include "models/robot.hpp"
#include "sim/sampling.hpp"

namespace gpm::hw {

// What to sample and how (constant).
struct SessionPlan {
  std::vector<Eigen::Vector2d> poses;  // mm; sample k is poses[k]
  sim::SamplingOptions options;        // move speed, settle criterion, averaging window
  std::array<JointMode, 3> modes{JointMode::kPosition, JointMode::kPosition, JointMode::kPosition};
  double profile_headroom = 0.5;       // fraction of the velocity/acceleration limits the moves use
};

// What a session did.
struct SessionResult {
  long taken = 0;    // samples recorded by this run
  long skipped = 0;  // already in the file (resume)
  double duration_s = 0.0;  // session time (simulated or wall)
};

// Runs the plan on hw (configured or not; left finalized). Samples go to log
// as they are taken. stop (optional) requests an emergency stop (e.g. SIGINT).
// Throws HardwareError (drives disabled, samples so far on disk) on failure.
SessionResult run_sampling_session(SafetySupervisor& hw, const SessionPlan& plan, SampleLog& log,
                                   const std::atomic<bool>* stop = nullptr);

}  // namespace gpm::hw
