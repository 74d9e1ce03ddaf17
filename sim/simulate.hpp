// One simulation run of a scenario (gpm simulate): build the actual robot and
// the twin, check every target, take the samples, follow the path, and write
// DIR/samples.csv, trajectory.csv, actual.yaml and model.xml.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "models/drive_margin.hpp"
#include "models/progress.hpp"
#include "models/robot.hpp"
#include "sim/sampling.hpp"
#include "sim/scenario.hpp"

namespace gpm::sim {

struct SimulationResult {
  Robot actual;
  std::string model_xml;
  std::vector<SampleRecord> samples;
  TrajectoryLog log;
  double max_violation_m = 0.0;  // over the whole run (every logged row)
  double max_torque = 0.0;       // N m, over the logged rows
  double simulated_s = 0.0;
  double sampling_s = 0.0;       // robot time of the sampling: from the first move to the last reading
};

// Throws InputError naming the pose (or path point) and the reason when a
// target is out of reach or within the singularity margins of the
// controller's robot or of the actual mechanism (the poses, and the points of
// the scenario's path; the excitation path of a trajectory plan is
// excitation_plan's).
void check_targets(const Scenario& s, const Robot& actual, const std::vector<Eigen::Vector2d>& poses);

// The same check for poses that the scenario key `key` names (error text
// "FILE: KEY: pose K (x, y): reason").
void check_poses_reach(const Scenario& s, const Robot& actual, const std::vector<Eigen::Vector2d>& poses,
                       const std::string& key);

// The same check at 201 points along a path that the scenario key `key` names.
void check_path_reach(const Scenario& s, const Robot& actual, const Path& path, const std::string& key);

// The drives of the scenario in position mode (servo.modes).
DriveMask position_drives(const Scenario& s);

// The excitation path of a trajectory plan through poses, from the
// controller's home (sim/waypoint_path.hpp), every point of it checked before
// anything moves against the robot's limits on the controller's model and
// against sampling.path_margin for the drives in position mode, widened by
// the model's tolerance (models/drive_margin.hpp): the controller's knowledge
// only, never the twin's actual mechanism, as on a real machine. Via points
// repair the segments that break it. Throws InputError (one line naming the
// file, the pose or segment and the reason) when the margin cannot be kept.
WaypointPath excitation_plan(const Scenario& s, const std::vector<Eigen::Vector2d>& poses,
                             PathRepair* repair = nullptr);

// Runs the scenario in memory; throws InputError for bad targets or
// parameters, SimError if the physics diverges, TrackingStop (with the
// samples and rows logged so far) if the tracking watch of
// servo.max_tracking_mm stops the robot. With a sink the trajectory
// rows are handed to it as they are produced and not kept (log.rows empty).
// With progress, the simulated time of each logged row is reported to it.
SimulationResult run_simulation(const Scenario& s, std::function<void(const LogRow&)> sink = nullptr,
                                Progress* progress = nullptr);

// samples.csv text: the docs/FORMATS.md contract (sample,theta_m1..3,x,y) followed by
// extra columns theta_a1..3 (true link angles), target_x, target_y, settled,
// tau1..3 (mean drive torque over the averaging window, N m), omega1..3 (the
// twin's true link speed, rad/s; nonzero for samples taken on the fly; the
// calibration differentiates the readings instead, calib/reading_rates.hpp),
// tau_last1..3 (the drive torque of the period just before the sample's
// instant, N m) and tau_between1..3 (the mean drive torque over the periods
// since the sample before, N m): on the fly the torques applied before the
// reading (tau1..3 is computed from it); at rest both equal tau1..3; then t
// (s, when the reading was taken: SampleRecord::t_s).
std::string samples_csv(const std::vector<SampleRecord>& samples);

// trajectory.csv header: t,x_des,y_des,x,y,theta_m1..3,tau1..3,violation_m,
// and with thermal growth growth,xa1,ya1,...,lb3 (the actual parameters at t).
std::string trajectory_header(bool thermal);
// One trajectory.csv line; thermal_reference (geometry at t = 0) adds the thermal columns.
std::string trajectory_line(const LogRow& row, const Geometry* thermal_reference);
// trajectory.csv text of an in-memory log.
std::string trajectory_csv(const TrajectoryLog& log);

// Writes the four files into dir (created if needed) all or nothing: they are
// written to a temporary folder first, then renamed; on failure nothing is left.
void write_simulation(const SimulationResult& r, const std::string& dir);
// The files write_simulation writes into DIR (samples.csv, trajectory.csv,
// actual.yaml, model.xml): for the check of DIR against every input.
const std::vector<std::string>& simulation_output_names();

// Runs the scenario and writes the same four files into dir, streaming
// trajectory.csv into the staging folder as it is produced (memory does not
// grow with the run's length; r.log.rows stays empty); all or nothing as
// write_simulation.
SimulationResult simulate_to_folder(const Scenario& s, const std::string& dir, Progress* progress = nullptr);

}  // namespace gpm::sim
