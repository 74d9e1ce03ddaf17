// Scenario files, simulation part (schema: scenarios/SCHEMA.md): the
// controller's robot, the actual parameters (explicit and/or a seeded random
// perturbation), physics, servo and encoder settings, the sampling plan, an
// optional continuous path, the log rate and the seed. The sections
// calibration, compensation, expect, hardware, outputs, render are accepted unparsed for
// later layers.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <yaml-cpp/yaml.h>

#include "models/drive_margin.hpp"
#include "models/parameters.hpp"
#include "models/robot.hpp"
#include "sim/sampling.hpp"
#include "sim/trajectory.hpp"
#include "sim/twin.hpp"
#include "sim/waypoint_path.hpp"

namespace gpm::sim {

// How the actual (true) parameters differ from the controller's robot.
struct ActualSpec {
  std::array<std::optional<double>, kNumParams> explicit_values{};  // replace these
  double sigma_base_mm = 0.0;     // Gaussian perturbation of xa*, ya*
  double sigma_link_mm = 0.0;     // ... of la*, lb*
  double sigma_offset_rad = 0.0;  // ... of dth*
  FreeMask keep;                  // never perturbed (default xa1 ya1 xa2 ya2: the frame)
};

// Where the samples are taken.
// kDesigned and kTrajectory take `count` poses designed at run time for the
// calibration (calib/excitation, resolved by the run layer into `poses`);
// kTrajectory samples them on the fly along a continuous excitation path.
enum class PosePattern { kDisc, kCircle, kLine, kList, kDesigned, kTrajectory };

// The design criterion of kDesigned and kTrajectory poses (`sampling.criterion`;
// calib/excitation/excitation.hpp). kAuto: kPositioning on the fly where the
// data sheet states an error once per joint revolution and the offsets are
// free, kWorst otherwise.
enum class DesignCriterion { kAuto, kWorst, kD, kPositioning };

struct SamplingPlan {
  PosePattern pattern = PosePattern::kDisc;
  Eigen::Vector2d centre{216.5, 250.0};
  double radius = 0.0;
  int count = 0;
  Eigen::Vector2d from = Eigen::Vector2d::Zero(), to = Eigen::Vector2d::Zero();
  std::vector<Eigen::Vector2d> poses;  // kList; kDesigned, kTrajectory once designed
  SamplingOptions options;
  // kTrajectory: the time law of the excitation path and how many drive loop
  // periods separate two samples.
  WaypointLimits path_limits;
  int sample_every = 4;
  // kTrajectory: what the excitation path keeps from losing control, for the
  // drives in position mode (`sampling.path_margin`, models/drive_margin.hpp).
  PathMargin margin;
  // kTrajectory: > 0, the path's first this many seconds are sampled first,
  // and the encoder offsets fitted to them before the path is sampled whole
  // (`sampling.offsets_first_s`; 0: none).
  double offsets_first_s = 0.0;
  DesignCriterion criterion = DesignCriterion::kAuto;  // kDesigned, kTrajectory
  // True when the poses still have to be designed (kDesigned, kTrajectory with no poses).
  bool needs_design() const {
    return (pattern == PosePattern::kDesigned || pattern == PosePattern::kTrajectory) && poses.empty();
  }
};

// The robot's normal job (`operation:`, for gpm monitor): a path repeated
// for duration_s.
struct Operation {
  Path path;
  double duration_s = 0.0;
};

struct Scenario {
  std::string file;       // the scenario file (for messages)
  std::string name;
  Robot controller;       // the controller's model (robot file)
  ActualSpec actual;
  TwinConfig twin;
  std::optional<SamplingPlan> sampling;
  std::optional<Path> path;  // continuous motion after the sampling
  std::optional<Operation> operation;  // normal operation (events: in twin.events)
  int log_every = 1;
  std::uint64_t seed = 1;
  // The twin loop stops the run when the end-effector, from the readings in
  // the controller's model, leaves the plan by more than this (mm;
  // `servo.max_tracking_mm`; 0: not watched).
  double max_tracking_mm = 20.0;
};

// Values a path map may leave out where a section gives defaults (the
// accuracy test path of gpm run); the scenario's own `path` gives them all.
struct PathDefaults {
  Eigen::Vector2d centre{216.5, 250.0};
  double radius = 60.0;     // mm
  double period_s = 4.0;    // circle
  double duration_s = 2.0;  // line
};

// Parses a path map (the schema of `path`, same ranges and messages) at
// keypath of file; missing keys take defaults.
Path path_from_yaml(const YAML::Node& n, const std::string& file, const std::string& keypath,
                    const PathDefaults& defaults);

// Loads and validates a scenario file; throws InputError naming the file,
// line and key path. Relative robot paths are taken from the file's folder.
Scenario load_scenario(const std::string& path);

// Builds a scenario from a parsed YAML root (file names it in errors).
Scenario scenario_from_yaml(const YAML::Node& root, const std::string& file,
                            const std::string& base_dir);

// Parses scenario text; base_dir resolves relative robot paths.
Scenario parse_scenario(const std::string& text, const std::string& file,
                        const std::string& base_dir);

// The actual robot: the controller's robot with explicit values applied and
// the others perturbed (seeded by derive_seed(seed, Stream::kActualParameters)); throws InputError if
// it cannot assemble at home.
Robot make_actual(const Scenario& scenario);

// The sample poses of a plan (disc poses from derive_seed(seed, Stream::kSamplePoses)).
std::vector<Eigen::Vector2d> plan_poses(const SamplingPlan& plan, std::uint64_t seed);

}  // namespace gpm::sim
