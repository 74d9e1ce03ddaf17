// The section-3 comparison for the section-2 search: sample poses on the same
// hardware (hw/procedures/sampling_session.hpp, the redundant joint read only) and
// estimate the three zero offsets alone by Levenberg-Marquardt with the ML
// cost (calib/lm.hpp), links and bases fixed at the controller's values.
#pragma once

#include <atomic>

#include <string>
#include <vector>

#include <Eigen/Core>

#include "hw/procedures/sampling_session.hpp"
#include "hw/safety_supervisor.hpp"

namespace gpm::hw {

// What the section-3 run did.
struct Section3Offsets {
  Eigen::Vector3d offsets = Eigen::Vector3d::Zero();  // estimated dth (rad)
  Eigen::Vector3d sigma = Eigen::Vector3d::Zero();    // their 1-sigma (rad)
  int motions = 0;                                    // poses visited
  double robot_time_s = 0.0;                          // session time (simulated or wall)
  bool converged = false;
};

// The sampling plan of the section-3 run: poses with sensor_joint torque-off
// (check_plan_poses checks it before a command's first motion).
SessionPlan section3_plan(const std::vector<Eigen::Vector2d>& poses, int sensor_joint);

// Samples poses on hw (left finalized) into samples_csv (a new file) with
// sensor_joint torque-off, then fits dth1..3 (ML cost). Throws HardwareError
// when the session fails (samples kept; Interrupted on a stop request
// through stop, see StopOnSignal), InputError for bad poses.
Section3Offsets section3_offsets(SafetySupervisor& hw, const std::vector<Eigen::Vector2d>& poses,
                                 int sensor_joint, const std::string& samples_csv,
                                 const std::atomic<bool>* stop = nullptr);

}  // namespace gpm::hw
