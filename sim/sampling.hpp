// Motion and sampling sessions on the twin: following paths with the drives
// updated at their loop rate, point-to-point moves with a settle criterion and
// encoder averaging (one sample per pose), and a trajectory log at the servo
// rate.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "models/errors.hpp"
#include "models/robot.hpp"
#include "sim/controller.hpp"
#include "sim/trajectory.hpp"
#include "sim/twin.hpp"

namespace gpm::sim {

// One row of trajectory.csv (at one drive loop instant).
struct LogRow {
  double t = 0.0;
  Eigen::Vector2d desired = Eigen::Vector2d::Zero();  // mm
  Eigen::Vector2d actual = Eigen::Vector2d::Zero();   // mm, true end-effector
  Eigen::Vector3d readings = Eigen::Vector3d::Zero(); // rad
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();   // N m
  double violation_m = 0.0;
  double growth = 0.0;  // thermal: relative length growth of the actual mechanism at t
  double growth_base = 0.0;  // thermal: relative growth of its base plate at t
};

// Log of a run: every `every`-th drive loop period. Rows are kept in memory
// (keep_rows) and/or handed to sink as they are produced (streaming to disk);
// count and the maxima cover every logged row either way.
struct TrajectoryLog {
  int every = 1;
  bool keep_rows = true;
  std::function<void(const LogRow&)> sink;  // optional
  std::vector<LogRow> rows;
  std::optional<Geometry> thermal_reference;  // with thermal growth: the geometry at t = 0
  long count = 0;
  double max_violation_m = 0.0;
  double max_torque = 0.0;  // N m, largest |tau_i|

  // Records one row (sink, maxima, and rows if keep_rows).
  void add(const LogRow& row);
};

// When a point-to-point move has come to rest.
struct SettleCriterion {
  double velocity_rad_s = 2e-3;  // every active joint slower than this ...
  double hold_s = 0.02;          // ... for this long, after the move ends
  double timeout_s = 2.0;        // give up waiting (the sample is marked unsettled)
};

// How samples are taken.
struct SamplingOptions {
  double move_speed_mm_s = 100.0;  // peak Cartesian speed of the moves
  SettleCriterion settle;
  double average_s = 0.05;         // encoder averaging window
};

// One sample: averaged readings and the true state over the window.
struct SampleRecord {
  long id = 0;
  Eigen::Vector2d target = Eigen::Vector2d::Zero();   // mm, commanded pose
  Eigen::Vector3d theta_m = Eigen::Vector3d::Zero();  // rad, averaged readings in [0, 2 pi)
  Eigen::Vector3d theta_a = Eigen::Vector3d::Zero();  // rad, averaged true active angles
  Eigen::Vector2d xy_mm = Eigen::Vector2d::Zero();    // mm, averaged true end-effector
  Eigen::Vector3d tau = Eigen::Vector3d::Zero();      // N m, mean drive torque over the window
  Eigen::Vector3d omega = Eigen::Vector3d::Zero();    // rad/s, true link speed (window mean; on the fly at the instant)
  // On the fly, the torques the drives applied before the reading instant (tau is the one computed from the
  // reading itself, applied after it): at rest both equal tau.
  Eigen::Vector3d tau_last = Eigen::Vector3d::Zero();     // N m, drive torque of the period just before the instant
  Eigen::Vector3d tau_between = Eigen::Vector3d::Zero();  // N m, mean drive torque over the periods since the sample before
  bool settled = false;
  double settle_time_s = 0.0;  // from the end of the move until the criterion held
  // s, when the reading was taken: on the fly the sample id x the sample interval (sample_every drive
  // periods, set by run_simulation); stop-and-go the middle of the averaging window (twin time).
  double t_s = 0.0;
  // s, when joint 1's reading was taken less when each joint's was: 0 where the three are read at one instant
  // (the twin, a latch); through drives polled one after another the lag of each (the calibration takes it out).
  Eigen::Vector3d read_lag_s = Eigen::Vector3d::Zero();
};

// A twin driven by a controller model, logging as it goes.
struct Session {
  const TwinModel& model;
  TwinState& state;
  const Robot& controller;
  TrajectoryLog* log = nullptr;  // optional
  Eigen::Vector2d desired;       // the last commanded end-effector position (mm)
  // Tracking watch: every drive loop period the end-effector is computed
  // from the three readings with the controller's model (the radical centre,
  // eq. 32-35: the torque-off joint's reading too, so a five-bar that changed
  // assembly mode shows) and compared with the desired point; beyond this
  // (mm) advance() throws TrackingStop. 0: not watched.
  double max_tracking_mm = 0.0;
  // The controller is the floor's oracle (its model the actual geometry):
  // its commands know the twin's transmission and encoder errors too
  // (sim/oracle_command.hpp).
  bool oracle = false;
  // Otherwise, when set: the readings the controller commands for the link
  // angles theta_a at its offsets dth (rad; its reading model's errors of the
  // reading's own angle compensated); unset: theta_a - dth (eq. 35).
  std::function<Eigen::Vector3d(const Eigen::Vector3d& theta_a, const Eigen::Vector3d& dth)> readings_for = nullptr;
};

// The end-effector left the plan by more than Session::max_tracking_mm: the
// run stops there (a real machine's drives would be disabled). What was
// measured before the stop is kept: sample_along() puts its samples here and
// run_simulation() the logged rows.
class TrackingStop : public Error {
 public:
  explicit TrackingStop(const std::string& what) : Error(what) {}
  std::vector<SampleRecord> samples;
  std::vector<LogRow> rows;
  double robot_time_s = 0.0;  // the robot's time until it was at rest again, where known (else 0)
  bool ended_early = false;   // a path on the fly ended early: retraced to its start, drives off normally
};

// A session starting at the twin's current state, the controller commanding
// its home (the drives hold their readings until the first command).
Session make_session(const TwinModel& model, TwinState& state, const Robot& controller,
                     TrajectoryLog* log);

// Runs one drive loop period with the given desired point; returns the
// snapshot sensed at its start (encoders, torques and kinematics together).
// Throws TrackingStop when the watch of s.max_tracking_mm trips.
TwinSnapshot advance(Session& s, const PathPoint& desired);

// Follows a path from its start to its end (the twin should already be at
// its start) at the drive loop rate.
void follow_path(Session& s, const Path& path);

// Moves to target, waits for the settle criterion, then averages the encoder
// readings and the true state over the window.
SampleRecord take_sample(Session& s, const Eigen::Vector2d& target, long id,
                         const SamplingOptions& options);

}  // namespace gpm::sim
