// One simulation run of a scenario (gpm simulate): build the actual robot and
// the twin, check every target, take the samples, follow the path, and write
// DIR/samples.csv, trajectory.csv, actual.yaml and model.xml.
#pragma once

#include <string>
#include <vector>

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
};

// Throws InputError naming the pose (or path point) and the reason when a
// target is out of reach or within the singularity margins of the
// controller's robot or of the actual mechanism.
void check_targets(const Scenario& s, const Robot& actual, const std::vector<Eigen::Vector2d>& poses);

// Runs the scenario in memory; throws InputError for bad targets or
// parameters, SimError if the physics diverges.
SimulationResult run_simulation(const Scenario& s);

// samples.csv text: the DESIGN.md contract (sample,theta_m1..3,x,y) followed by
// extra columns theta_a1..3 (true active angles), target_x, target_y, settled.
std::string samples_csv(const std::vector<SampleRecord>& samples);

// trajectory.csv text: t,x_des,y_des,x,y,theta_m1..3,tau1..3,violation_m.
std::string trajectory_csv(const TrajectoryLog& log);

// Writes the four files into dir (created if needed) all or nothing: they are
// written to a temporary folder first, then renamed; on failure nothing is left.
void write_simulation(const SimulationResult& r, const std::string& dir);

}  // namespace gpm::sim
