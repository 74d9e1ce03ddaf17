#include "calib/positioning_error.hpp"

#include <cmath>
#include <vector>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "models/errors.hpp"
#include "models/kinematics.hpp"

namespace gpm::calib {
namespace {

// The readings the model commands for p (eq. 31 and eq. 35); nullopt when the
// model cannot reach p.
std::optional<Eigen::Vector3d> commanded(const Geometry& model, const Branches& branch, const Eigen::Vector2d& p) {
  const auto q = try_inverse_kinematics(model, p, branch);
  if (!q) return std::nullopt;
  return readings_from_active(model, q->theta_a);
}

// Where the actual robot stands when its three drives, equally stiff, hold
// readings theta_m: the point whose actual joint angles are nearest to
// theta_m + dth in the least-squares sense (the drives' springs balance),
//   p <- p + (J'J)^-1 J' (theta_a* - theta_a(p)),  J = d theta_a / d p (eq. 11),
// by Gauss-Newton from p0; nullopt when the actual robot cannot reach it.
std::optional<Eigen::Vector2d> reached(const Robot& actual, const Eigen::Vector3d& theta_m, Eigen::Vector2d p) {
  const Eigen::Vector3d target = active_from_readings(actual.geometry, theta_m);  // eq. 35
  for (int it = 0; it < 8; ++it) {
    const auto q = try_inverse_kinematics(actual.geometry, p, actual.branch);
    if (!q) return std::nullopt;
    Eigen::Vector3d r;
    for (int c = 0; c < kNumChains; ++c) r[c] = wrap_pi(target[c] - q->theta_a[c]);
    const Matrix32d J = active_jacobian(actual.geometry, *q);
    const Eigen::Vector2d dp = (J.transpose() * J).ldlt().solve(J.transpose() * r);
    p += dp;
    if (dp.norm() < 1e-12) break;
  }
  return p;
}

// Where the actual robot stands when the model commands p.
std::optional<Eigen::Vector2d> position_for(const Robot& actual, const Geometry& model, const Branches& branch,
                                            const Eigen::Vector2d& p) {
  const auto theta_m = commanded(model, branch, p);
  if (!theta_m) return std::nullopt;
  return reached(actual, *theta_m, p);
}

std::vector<Eigen::Vector2d> grid(const WorkspaceDisc& d) {
  std::vector<Eigen::Vector2d> v;
  const int n = static_cast<int>(std::floor(d.radius_mm / d.step_mm));
  for (int ix = -n; ix <= n; ++ix)
    for (int iy = -n; iy <= n; ++iy) {
      const Eigen::Vector2d off(ix * d.step_mm, iy * d.step_mm);
      if (off.norm() <= d.radius_mm + 1e-9) v.push_back(d.centre + off);
    }
  return v;
}

// d p_actual / d model parameter k by central differences (mm per mm or rad).
std::optional<Eigen::Matrix<double, 2, kNumParams>> sensitivity(const Robot& actual, const Robot& model,
                                                                const Eigen::Vector2d& p) {
  Eigen::Matrix<double, 2, kNumParams> J;
  for (int k = 0; k < kNumParams; ++k) {
    const double h = is_offset(k) ? 1e-7 : 1e-5;
    Geometry up = model.geometry, down = model.geometry;
    up[k] += h, down[k] -= h;
    const auto a = position_for(actual, up, model.branch, p), b = position_for(actual, down, model.branch, p);
    if (!a || !b) return std::nullopt;
    J.col(k) = (*a - *b) / (2.0 * h);
  }
  return J;
}

}  // namespace

PositioningError positioning_error(const Robot& actual, const Robot& model, const WorkspaceDisc& disc,
                                   const std::optional<Eigen::Matrix<double, kNumParams, kNumParams>>& covariance,
                                   const std::optional<Eigen::Matrix<double, kNumParams, kNumParams>>& carried) {
  PositioningError out;
  double sum2 = 0.0, sigma2 = 0.0, maha = 0.0, carried2 = 0.0;
  for (const Eigen::Vector2d& p : grid(disc)) {
    const auto at = position_for(actual, model.geometry, model.branch, p);
    if (!at) continue;
    const Eigen::Vector2d e = *at - p;
    ++out.points;
    sum2 += e.squaredNorm();
    out.max_um = std::max(out.max_um, e.norm() * 1e3);
    out.map.push_back({p, e, 0.0});
    if (!covariance) continue;
    const auto J = sensitivity(actual, model, p);
    if (!J) continue;
    const Eigen::Matrix2d S = *J * *covariance * J->transpose();
    sigma2 += S.trace() / 2.0;
    out.map.back().sigma_um = std::sqrt(S.trace() / 2.0) * 1e3;
    maha += e.dot(S.ldlt().solve(e)) / 2.0;
    if (carried) carried2 += (*J * *carried * J->transpose()).trace() / 2.0;
  }
  if (out.points == 0)
    throw InputError(fmt::format("positioning error: no point of the {} mm disc round ({}, {}) is reachable",
                                 disc.radius_mm, disc.centre.x(), disc.centre.y()));
  out.rms_um = std::sqrt(sum2 / out.points) * 1e3;
  if (covariance) {
    out.stated_sigma_rms_um = std::sqrt(sigma2 / out.points) * 1e3;
    out.normalised_rms = std::sqrt(maha / out.points);
    out.carried_sigma_rms_um = std::sqrt(carried2 / out.points) * 1e3;
  }
  return out;
}

Eigen::Matrix<double, kNumParams, kNumParams> positioning_weight(const Robot& robot, const WorkspaceDisc& disc) {
  Eigen::Matrix<double, kNumParams, kNumParams> W = Eigen::Matrix<double, kNumParams, kNumParams>::Zero();
  int points = 0;
  for (const Eigen::Vector2d& p : grid(disc)) {
    const auto J = sensitivity(robot, robot, p);
    if (!J) continue;
    W += J->transpose() * *J;
    ++points;
  }
  if (points == 0)
    throw InputError(fmt::format("positioning weight: no point of the {} mm disc round ({}, {}) is reachable",
                                 disc.radius_mm, disc.centre.x(), disc.centre.y()));
  return W / points;
}

std::optional<PositioningError> stated_positioning(const Robot& robot, const Result& result) {
  if (!result.covariance) return std::nullopt;
  Robot calibrated = robot;
  calibrated.geometry = result.geometry;
  try {
    return positioning_error(calibrated, calibrated, WorkspaceDisc{robot.home}, result.covariance,
                             result.carried_covariance);
  } catch (const InputError&) {
    return std::nullopt;
  }
}

std::string positioning_csv(const PositioningError& e) {
  std::string out = "x_mm,y_mm,error_x_um,error_y_um,error_um,sigma_um\n";
  for (const PositioningPoint& m : e.map) {
    const Eigen::Vector2d um = m.error * 1e3;
    out += fmt::format("{},{},{},{},{},{}\n", m.p.x(), m.p.y(), um.x(), um.y(), um.norm(), m.sigma_um);
  }
  return out;
}

}  // namespace gpm::calib
