// What a user gets from a calibration: the noise-free positioning error of
// the calibrated model over the workspace. At every point p of a grid over a
// disc round the home pose the controller commands the readings its model
// gives for p (inverse kinematics, eq. 31, and theta_m = theta_a - dth,
// eq. 35); the actual robot, its three drives (equally stiff) holding those
// readings, stands where its actual joint angles come nearest to them in the
// least-squares sense (the drives' springs balance; with consistent readings
// this is the forward kinematics, eq. 32-34). The error is the distance to
// p. With the calibration's covariance the same map
// gives the positioning 1-sigma the result states, so the two can be
// compared point by point.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "calib/problem.hpp"
#include "models/parameters.hpp"
#include "models/robot.hpp"

namespace gpm::calib {

// The grid: points step_mm apart within radius_mm of centre.
struct WorkspaceDisc {
  Eigen::Vector2d centre{216.5, 250.0};
  double radius_mm = 80.0;
  double step_mm = 10.0;
};

// One point of the map: where the model commanded the robot, how far off
// the actual robot stands, and the stated 1-sigma there.
struct PositioningPoint {
  Eigen::Vector2d p = Eigen::Vector2d::Zero();      // commanded position (mm)
  Eigen::Vector2d error = Eigen::Vector2d::Zero();  // actual - commanded (mm)
  double sigma_um = 0.0;  // sqrt(trace(J C J') / 2) with a covariance, else 0
};

struct PositioningError {
  std::vector<PositioningPoint> map;  // every reachable grid point, row by row
  int points = 0;            // grid points the model reaches
  double rms_um = 0.0;       // RMS of |p_actual - p| over the points
  double max_um = 0.0;
  // With a covariance: RMS over the same points of the stated 1-sigma of the
  // position, sqrt(trace(J C J') / 2) per axis, and the RMS of the
  // Mahalanobis distance e' (J C J')^-1 e / 2 (about 1 when the stated
  // 1-sigma is honest: the squared distance is chi-square with 2 dof).
  double stated_sigma_rms_um = 0.0;
  double normalised_rms = 0.0;
  // With a carried covariance too: the same RMS of the 1-sigma it alone
  // gives, its share of stated_sigma_rms_um in quadrature (0 without).
  double carried_sigma_rms_um = 0.0;
};

// Positioning error of model (the calibrated robot) on actual over disc.
// covariance (15 x 15, zero rows for fixed parameters), when given, is the
// calibration's; the 1-sigma map is taken by central differences of the
// commanded position in the model's parameters; carried, when given, is the
// part of it an error carried unestimated adds (calib::Result::
// carried_covariance). Throws InputError if no grid point is reachable.
PositioningError positioning_error(const Robot& actual, const Robot& model, const WorkspaceDisc& disc,
                                   const std::optional<Eigen::Matrix<double, kNumParams, kNumParams>>& covariance = {},
                                   const std::optional<Eigen::Matrix<double, kNumParams, kNumParams>>& carried = {});

// Mean over the disc's points that robot reaches of J' J, J = d p / d
// geometry (mm per mm or rad, robot's model on robot itself): for a geometry
// covariance C, trace(W C) is the mean square positioning error it causes
// (the RMS of |e| squared, mm^2). Throws InputError if no point is reachable.
Eigen::Matrix<double, kNumParams, kNumParams> positioning_weight(const Robot& robot, const WorkspaceDisc& disc);

// The positioning 1-sigma result states over the disc round robot's home,
// by the calibrated model's own sensitivities (robot with result's geometry
// as both actual and model: no truth to judge it by, its error 0); nullopt
// without a covariance or where that model reaches no point of the disc.
std::optional<PositioningError> stated_positioning(const Robot& robot, const Result& result);

// The map as CSV text: a header `x_mm,y_mm,error_x_um,error_y_um,error_um,sigma_um`
// and a row per point (sigma_um 0 without a covariance), numbers in their
// shortest exact form.
std::string positioning_csv(const PositioningError& e);

}  // namespace gpm::calib
