#include "hw/procedures/section3_offsets.hpp"

#include <cmath>
#include <numbers>

#include "calib/lm.hpp"
#include "hw/procedures/sample_log.hpp"
#include "hw/procedures/sampling_session.hpp"

namespace gpm::hw {

SessionPlan section3_plan(const std::vector<Eigen::Vector2d>& poses, int sensor_joint) {
  SessionPlan plan;
  plan.poses = poses;
  for (int k = 0; k < 3; ++k) plan.modes[k] = k == sensor_joint ? JointMode::kTorqueOff : JointMode::kPosition;
  return plan;
}

Section3Offsets section3_offsets(SafetySupervisor& hw, const std::vector<Eigen::Vector2d>& poses,
                                 int sensor_joint, const std::string& samples_csv,
                                 const std::atomic<bool>* stop) {
  const SessionPlan plan = section3_plan(poses, sensor_joint);
  Section3Offsets out;
  std::vector<Eigen::Vector3d> readings;
  {
    SampleLog log(samples_csv, false);
    const SessionResult s = run_sampling_session(hw, plan, log, stop);
    out.motions = static_cast<int>(s.taken);
    out.robot_time_s = s.duration_s;
    for (const auto& [id, row] : log.recorded()) readings.push_back(row.theta_m);  // as written, in id order
  }
  calib::Problem p;
  p.theta_m = readings;
  p.start = hw.controller().geometry;
  for (int i = 0; i < 3; ++i) p.free.set(dth(i));
  calib::LmOptions o;
  o.cost = calib::Cost::kML;
  const calib::Result r = calib::calibrate_lm(p, o);
  for (int i = 0; i < 3; ++i) {
    out.offsets[i] = r.geometry[dth(i)];
    out.sigma[i] = r.sigma[dth(i)];
  }
  out.converged = r.converged;
  return out;
}

}  // namespace gpm::hw
