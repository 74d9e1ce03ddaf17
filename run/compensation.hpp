// Compensation, the number users care about: the twin (actual parameters)
// driven by a controller model — nominal or calibrated — measured on test
// poses (static accuracy after settling) and along a test path (tracking),
// with the servos' internal preload.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "calib/reading_model.hpp"
#include "models/progress.hpp"
#include "models/robot.hpp"
#include "sim/sampling.hpp"
#include "sim/trajectory.hpp"
#include "sim/twin.hpp"

namespace gpm::scenario {

// What to measure.
struct CompensationPlan {
  std::vector<Eigen::Vector2d> poses;  // static test poses (mm)
  sim::Path path;                      // tracking test path
  sim::SamplingOptions sampling;       // move, settle, average
  double move_speed_mm_s = 100.0;
};

// Accuracy of one controller model on the twin.
struct Accuracy {
  std::string label;
  // Static: |true end-effector - target| after settling, per pose (um).
  std::vector<double> static_error_um;
  double static_rms_um = 0.0, static_max_um = 0.0;
  // Tracking: |true - desired| along the path at the servo rate (um).
  double path_rms_um = 0.0, path_max_um = 0.0;
  // Internal preload |P tau| (N m): the part of the three drive torques that
  // produces no end-effector force, P = I - J (J'J)^-1 J' with J the active
  // Jacobian (eq. 11, 15) of the actual mechanism. Servos fighting over an
  // inconsistent model hold it; RMS at the static poses and along the path.
  double static_preload_rms_nm = 0.0;
  double path_preload_rms_nm = 0.0;
  sim::TrajectoryLog path_log;  // the path run, for figures and video
};

// Runs the plan on a fresh twin of `actual` driven by `controller`; with
// progress, reports the test poses done (then the path, one more step). With
// max_tracking_mm > 0 the twin loop's tracking watch is on
// (sim::Session::max_tracking_mm: sim::TrackingStop when it trips); with
// oracle the controller (the actual geometry) knows the twin's transmission
// and encoder errors too (sim::Session::oracle: the floor); with
// drive_train, the controller compensates that reading model's drive-train
// harmonics (calib::reading_at: the calibration's estimates, as the
// monitor takes them).
Accuracy measure_accuracy(const Robot& actual, const sim::TwinConfig& twin,
                          const Robot& controller, const CompensationPlan& plan,
                          unsigned long long seed, const std::string& label, Progress* progress = nullptr,
                          double max_tracking_mm = 0.0, bool oracle = false,
                          const calib::ReadingModel* drive_train = nullptr);

// The 95 % interval of rms(a) / rms(b), a and b errors at the same poses
// (paired by index, equal sizes): the percentile bootstrap over the poses,
// `resamples` draws of them with replacement from a generator seeded with
// seed. Throws InputError for sizes that differ, no poses or resamples < 40.
std::array<double, 2> rms_ratio_interval(const std::vector<double>& a, const std::vector<double>& b,
                                         std::uint64_t seed, int resamples = 2000);

// |P tau| for torques tau at joint configuration q of geometry g (N m).
double internal_preload(const Geometry& g, const Eigen::Vector2d& p, const Eigen::Vector3d& tau,
                        const Branches& branch);

}  // namespace gpm::scenario
