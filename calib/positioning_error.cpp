#include "calib/positioning_error.hpp"

#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "models/errors.hpp"
#include "models/kinematics.hpp"

namespace gpm::calib {
namespace {

constexpr std::array<std::pair<int, int>, 3> kPairs{{{0, 1}, {0, 2}, {1, 2}}};

// Where the actual robot stands when drives i and j hold the readings the
// model commands for p; nullopt if the model cannot reach p or the actual
// chains do not close.
std::optional<Eigen::Vector2d> reached(const Robot& actual, const Geometry& model, const Branches& branch,
                                       const Eigen::Vector2d& p, int i, int j) {
  Eigen::Vector3d theta_a;
  for (int c = 0; c < kNumChains; ++c) {
    const auto q = try_chain_ik(model, c, p, branch[static_cast<size_t>(c)]);
    if (!q) return std::nullopt;
    theta_a[c] = q->theta_a;
  }
  const Eigen::Vector3d theta_m = readings_from_active(model, theta_a);                  // eq. 35
  const Eigen::Vector3d actual_theta_a = active_from_readings(actual.geometry, theta_m);  // eq. 35
  const int mode = assembly_mode(actual.geometry, actual_theta_a, p, i, j);
  return forward_kinematics_two(actual.geometry, actual_theta_a, i, j, mode);
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
                                                                const Eigen::Vector2d& p, int i, int j) {
  Eigen::Matrix<double, 2, kNumParams> J;
  for (int k = 0; k < kNumParams; ++k) {
    const double h = is_offset(k) ? 1e-7 : 1e-5;
    Geometry up = model.geometry, down = model.geometry;
    up[k] += h, down[k] -= h;
    const auto a = reached(actual, up, model.branch, p, i, j), b = reached(actual, down, model.branch, p, i, j);
    if (!a || !b) return std::nullopt;
    J.col(k) = (*a - *b) / (2.0 * h);
  }
  return J;
}

}  // namespace

PositioningError positioning_error(const Robot& actual, const Robot& model, const WorkspaceDisc& disc,
                                   const std::optional<Eigen::Matrix<double, kNumParams, kNumParams>>& covariance) {
  PositioningError out;
  double sum2 = 0.0, sigma2 = 0.0, maha = 0.0;
  for (const Eigen::Vector2d& p : grid(disc)) {
    for (const auto& [i, j] : kPairs) {
      const auto at = reached(actual, model.geometry, model.branch, p, i, j);
      if (!at) continue;
      const Eigen::Vector2d e = *at - p;
      ++out.points;
      sum2 += e.squaredNorm();
      out.max_um = std::max(out.max_um, e.norm() * 1e3);
      if (!covariance) continue;
      const auto J = sensitivity(actual, model, p, i, j);
      if (!J) continue;
      const Eigen::Matrix2d S = *J * *covariance * J->transpose();
      sigma2 += S.trace() / 2.0;
      maha += e.dot(S.ldlt().solve(e)) / 2.0;
    }
  }
  if (out.points == 0)
    throw InputError(fmt::format("positioning error: no point of the {} mm disc round ({}, {}) is reachable",
                                 disc.radius_mm, disc.centre.x(), disc.centre.y()));
  out.rms_um = std::sqrt(sum2 / out.points) * 1e3;
  if (covariance) {
    out.stated_sigma_rms_um = std::sqrt(sigma2 / out.points) * 1e3;
    out.normalised_rms = std::sqrt(maha / out.points);
  }
  return out;
}

}  // namespace gpm::calib
