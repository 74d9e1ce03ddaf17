// The robot's geometry learnt from the first samples of a path sampled on
// the fly, before the controller drives the whole path (the offsets stage,
// run/offsets_first.hpp). Three readings of a 2-DOF mechanism close its
// loops only under the right geometry; the controller's (data-sheet)
// geometry is off by its tolerance, which near a singular pose of the
// position joints moves the end-effector tens of millimetres from its plan.
// The filter turns each sample's closure misfit into an estimate of the
// geometry with its covariance (prior: the controller's geometry and the
// tolerance the path planner widens it by; never the robot's truth), so that
// a few samples in one corner of the workspace move each parameter only as
// far as they show it, where a fit of the offsets alone would load the
// links' errors onto them.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "models/drive_margin.hpp"
#include "models/parameters.hpp"

namespace gpm::calib {

// What the filter knows before the first sample and how much it trusts each (constant).
struct GeometryFilterSettings {
  // Prior 1-sigma of each parameter about the controller's value: the
  // tolerance the excitation path's margin covers (sampling.path_margin).
  ModelTolerance prior;
  // 1-sigma of one update's closure misfit that the geometry does not
  // explain (rad, the ML residual's unit): the drive train's twist under
  // load (a 1e4 N m/rad reducer at up to 10 N m), shared by the samples of
  // about 10 ms, which is why one sample per 10 ms updates it.
  double misfit_sigma_rad = 2e-3;
  // Parameters held at the controller's value: the frame (readings cannot
  // see the mechanism's position, rotation or scale).
  FreeMask held = parse_param_list("xa1,ya1,xa2,ya2", "held");
};

// An extended Kalman filter of a constant state x (the free parameters of
// Geometry) with the ML closure residual of one sample as its measurement
// (paper eq. 1 and 35; calib/residuals.hpp MlResidual):
//   r(x) = P(theta_m, x) / |dP / d theta_m|,   measured value 0,
// P the power of the radical centre (models/closure.hpp); H = dr/dx by
// forward differences, R = misfit_sigma^2, and
//   K = Sigma H^T / (H Sigma H^T + R),  x += K (0 - r),  Sigma = (I - K H) Sigma (I - K H)^T + K R K^T.
class GeometryFilter {
 public:
  // Starts at controller's geometry with the prior of settings.
  explicit GeometryFilter(const Geometry& controller, const GeometryFilterSettings& settings = {});

  // One sample's three readings (rad). Readings whose loops have no radical
  // centre (collinear elbows) or a flat closure leave the estimate as it is.
  void update(const Eigen::Vector3d& theta_m);

  // The geometry learnt so far.
  const Geometry& geometry() const { return geometry_; }
  // Covariance of the free parameters (mm and rad; order: free_index()).
  const Eigen::MatrixXd& covariance() const { return sigma_; }
  // The free parameters' indices in Geometry, in the covariance's order.
  const std::vector<int>& free_index() const { return free_; }
  // Samples that updated the estimate.
  long updates() const { return updates_; }

 private:
  Geometry geometry_;
  std::vector<int> free_;
  Eigen::MatrixXd sigma_;
  double misfit_variance_ = 0.0;
  long updates_ = 0;
};

}  // namespace gpm::calib
