// The in-process twin as hardware: gpm run and gpm monitor drive the twin of
// a scenario through the safety supervisor and the twin backend
// (hw/backends/twin_backend.hpp), with the procedures of hw/procedures, exactly
// as they drive real drives (`--hardware HW.yaml` with `backend: twin` runs
// the same loop). What only the twin knows (its true poses, the trajectory
// log of desired against actual, the geometry its events and growth give)
// comes from the backend's observer (TwinTruth), never from the
// HardwareState a real drive gives.
#pragma once

#include <array>
#include <deque>
#include <limits>
#include <map>
#include <memory>

#include "hw/backends/twin_backend.hpp"
#include "hw/procedures/sampling_session.hpp"
#include "hw/safety_supervisor.hpp"
#include "models/progress.hpp"
#include "sim/sampling.hpp"
#include "sim/scenario.hpp"

namespace gpm::scenario {

// A scenario's twin behind its safety supervisor.
struct TwinHardware {
  std::unique_ptr<hw::SafetySupervisor> robot;
  hw::TwinBackend* twin = nullptr;  // the backend robot supervises (owned by robot)
};

// The scenario's drives as joint modes of the hardware interface: position,
// else torque-off (a joint the scenario gives a constant torque keeps it in
// the twin: hw::TwinBackend).
std::array<hw::JointMode, 3> twin_joint_modes(const sim::Scenario& s);

// The safety limits of the in-process twin: the scenario's tracking bound
// (servo.max_tracking_mm; 0: not watched, the widest bound) and the widest
// values a hardware file may state for the rest (the scenario's own checks,
// its reach and path margin, keep the plan safe before anything moves), the
// watchdog at 0.1 s hold and 0.5 s disable; a hardware file with these
// limits (hw::safety_limits_to_yaml) runs the same loop.
hw::SafetyLimits twin_safety_limits(const sim::Scenario& s, const Robot& controller);

// The twin of s (its mechanism actual, assembled at actual.home; its servo,
// encoders, effects and events; its noise seed) at the drive loop rate,
// commanded with the controller's model, behind twin_safety_limits.
TwinHardware make_twin_hardware(const sim::Scenario& s, const Robot& actual, const Robot& controller);

// The twin's truth of one sample: the mean over the cycles it stands for.
struct SampleTruth {
  Eigen::Vector3d theta_a = Eigen::Vector3d::Zero();  // rad, true active angles
  Eigen::Vector2d xy_mm = Eigen::Vector2d::Zero();    // mm, true end-effector
  Eigen::Vector3d omega = Eigen::Vector3d::Zero();    // rad/s, true link speeds
  Eigen::Vector3d tau = Eigen::Vector3d::Zero();      // N m, drive torques applied
  double t_s = 0.0;                                   // s, twin time (mean)
};

// Records what only the twin knows from its backend's snapshot after every
// read: trajectory log rows (every log->every reads; desired: where the
// command in force puts the controller's end-effector) and, through hook(),
// the truth of each sample as a session logs it. Observes th until destroyed.
class TwinTruth {
 public:
  TwinTruth(TwinHardware& th, sim::TrajectoryLog* log, gpm::Progress* progress = nullptr);
  ~TwinTruth();
  TwinTruth(const TwinTruth&) = delete;
  TwinTruth& operator=(const TwinTruth&) = delete;

  // The hook a session calls as it logs each sample (hw::SampleHook).
  hw::SampleHook hook();
  const std::map<long, SampleTruth>& samples() const { return samples_; }
  // Twin time of the last read (s).
  double time_s() const { return time_s_; }

 private:
  void on_read(const sim::TwinSnapshot& snap);
  void on_sample(long id, long cycles);

  TwinHardware& th_;
  sim::TrajectoryLog* log_;
  gpm::Progress* progress_;
  std::deque<sim::TwinSnapshot> recent_;  // the reads since the last sample
  std::map<long, SampleTruth> samples_;
  Eigen::Vector2d desired_ = Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
  long reads_ = 0;
  double time_s_ = 0.0;
};

}  // namespace gpm::scenario
