#include "models/kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/SVD>
#include <fmt/format.h>

#include "models/closure.hpp"

namespace gpm {

using Eigen::Vector2d;
using Eigen::Vector3d;

double wrap_pi(double a) {
  constexpr double two_pi = 2.0 * std::numbers::pi;
  a = std::fmod(a, two_pi);
  if (a <= -std::numbers::pi) a += two_pi;
  if (a > std::numbers::pi) a -= two_pi;
  return a;
}

double wrap_2pi(double a) {
  constexpr double two_pi = 2.0 * std::numbers::pi;
  a = std::fmod(a, two_pi);
  if (a < 0.0) a += two_pi;
  return a;
}

std::optional<ChainAngles> try_chain_ik(const Geometry& g, int i, const Vector2d& p, int branch) {
  const Vector2d A_p = p - g.A(i);
  const double d = A_p.norm();
  const double la_i = g.la_(i), lb_i = g.lb_(i);
  if (!std::isfinite(d) || d > la_i + lb_i || d < std::abs(la_i - lb_i) || d == 0.0) return std::nullopt;
  const double phi = std::atan2(A_p.y(), A_p.x());
  const double c = std::clamp((la_i * la_i + d * d - lb_i * lb_i) / (2.0 * la_i * d), -1.0, 1.0);
  const double alpha = std::acos(c);
  ChainAngles out;
  out.theta_a = wrap_2pi(phi + (branch >= 0 ? alpha : -alpha));
  const Vector2d B = g.A(i) + la_i * Vector2d(std::cos(out.theta_a), std::sin(out.theta_a));
  const Vector2d B_p = p - B;
  out.theta_b = std::atan2(B_p.y(), B_p.x());  // eq. 34
  return out;
}

ChainAngles chain_ik(const Geometry& g, int i, const Vector2d& p, int branch) {
  if (auto r = try_chain_ik(g, i, p, branch)) return *r;
  if (!p.allFinite())
    throw ReachError(fmt::format("target ({}, {}) is not a position: x and y must be finite numbers in mm", p.x(), p.y()),
                     i, std::numeric_limits<double>::infinity());
  const double d = (p - g.A(i)).norm();
  const double outer = g.la_(i) + g.lb_(i);
  const double inner = std::abs(g.la_(i) - g.lb_(i));
  const double shortfall = d > outer ? d - outer : inner - d;
  throw ReachError(fmt::format("chain {}: target ({:.4f}, {:.4f}) is out of reach by {:.4f} mm "
                               "(distance from A{} is {:.4f} mm; reach is {:.4f} to {:.4f} mm)",
                               i + 1, p.x(), p.y(), shortfall, i + 1, d, inner, outer),
                   i, shortfall);
}

JointAngles inverse_kinematics(const Geometry& g, const Vector2d& p, const Branches& branch) {
  JointAngles q;
  for (int i = 0; i < kNumChains; ++i) {
    const ChainAngles c = chain_ik(g, i, p, branch[static_cast<size_t>(i)]);
    q.theta_a[i] = c.theta_a;
    q.theta_b[i] = c.theta_b;
  }
  return q;
}

std::optional<JointAngles> try_inverse_kinematics(const Geometry& g, const Vector2d& p, const Branches& branch) {
  JointAngles q;
  for (int i = 0; i < kNumChains; ++i) {
    const std::optional<ChainAngles> c = try_chain_ik(g, i, p, branch[static_cast<size_t>(i)]);
    if (!c) return std::nullopt;
    q.theta_a[i] = c->theta_a;
    q.theta_b[i] = c->theta_b;
  }
  return q;
}

std::array<Vector2d, 3> elbows(const Geometry& g, const Vector3d& theta_a) {
  std::array<Vector2d, 3> B;
  for (int i = 0; i < kNumChains; ++i) {
    B[static_cast<size_t>(i)] =
        g.A(i) + g.la_(i) * Vector2d(std::cos(theta_a[i]), std::sin(theta_a[i]));
  }
  return B;
}

std::optional<ForwardResult> forward_kinematics(const Geometry& g, const Vector3d& theta_a) {
  const auto B = elbows(g, theta_a);
  const double Bx[3] = {B[0].x(), B[1].x(), B[2].x()};
  const double By[3] = {B[0].y(), B[1].y(), B[2].y()};
  const double lb[3] = {g.lb_(0), g.lb_(1), g.lb_(2)};
  const RadicalCentre<double> rc = radical_centre(Bx, By, lb);  // eq. 32-33
  if (!rc.ok) return std::nullopt;
  ForwardResult out;
  out.p = Vector2d(rc.Ox, rc.Oy);
  for (int i = 0; i < kNumChains; ++i) out.theta_b[i] = passive_angle(rc.Ox, rc.Oy, Bx[i], By[i]);  // eq. 34
  out.power = rc.P;
  return out;
}

std::optional<std::array<Vector2d, 2>> circle_intersections(const Vector2d& c1, double r1,
                                                            const Vector2d& c2, double r2) {
  const Vector2d d = c2 - c1;
  const double dist_sq = d.squaredNorm();
  const double dist = std::sqrt(dist_sq);
  if (dist == 0.0 || dist > r1 + r2 || dist < std::abs(r1 - r2)) return std::nullopt;
  // Foot of the common chord along c1 -> c2, then half-chord perpendicular.
  const double a = (r1 * r1 - r2 * r2 + dist_sq) / (2.0 * dist);
  const double h = std::sqrt(std::max(0.0, r1 * r1 - a * a));
  const Vector2d e = d / dist;
  const Vector2d n(-e.y(), e.x());  // left of c1 -> c2
  const Vector2d foot = c1 + a * e;
  return std::array<Vector2d, 2>{foot + h * n, foot - h * n};
}

int assembly_mode(const Geometry& g, const Vector3d& theta_a, const Vector2d& p, int i, int j) {
  const auto B = elbows(g, theta_a);
  const Vector2d bi_bj = B[static_cast<size_t>(j)] - B[static_cast<size_t>(i)];
  const Vector2d bi_p = p - B[static_cast<size_t>(i)];
  return bi_bj.x() * bi_p.y() - bi_bj.y() * bi_p.x() >= 0.0 ? +1 : -1;
}

std::optional<Vector2d> forward_kinematics_two(const Geometry& g, const Vector3d& theta_a, int i,
                                               int j, int mode) {
  const auto B = elbows(g, theta_a);
  const auto x = circle_intersections(B[static_cast<size_t>(i)], g.lb_(i),
                                      B[static_cast<size_t>(j)], g.lb_(j));
  if (!x) return std::nullopt;
  return mode >= 0 ? (*x)[0] : (*x)[1];
}

Matrix32d active_jacobian(const Geometry& g, const JointAngles& q) {
  Matrix32d J;
  for (int i = 0; i < kNumChains; ++i) {
    const double s = g.la_(i) * std::sin(q.theta_a[i] - q.theta_b[i]);
    J(i, 0) = -std::cos(q.theta_b[i]) / s;  // eq. 11
    J(i, 1) = -std::sin(q.theta_b[i]) / s;
  }
  return J;
}

Conditioning conditioning(const Geometry& g, const JointAngles& q) {
  Conditioning c;
  Matrix32d U;
  for (int i = 0; i < kNumChains; ++i) {
    c.transmission[i] = std::abs(std::sin(q.theta_a[i] - q.theta_b[i]));
    U(i, 0) = std::cos(q.theta_b[i]);
    U(i, 1) = std::sin(q.theta_b[i]);
  }
  c.min_transmission = c.transmission.minCoeff();
  if (!U.allFinite() || !q.theta_a.allFinite()) {  // no measure of angles that are not numbers
    c.direct = c.jacobian_condition = c.min_transmission = std::numeric_limits<double>::quiet_NaN();
    return c;
  }
  const Eigen::JacobiSVD<Matrix32d> svd_u(U);
  c.direct = svd_u.singularValues()(1) / std::sqrt(1.5);
  if (c.min_transmission > 0.0) {
    const Eigen::JacobiSVD<Matrix32d> svd_j(active_jacobian(g, q));
    const auto s = svd_j.singularValues();
    c.jacobian_condition = s(1) > 0.0 ? s(0) / s(1) : INFINITY;
  } else {
    c.jacobian_condition = INFINITY;
  }
  return c;
}

Reach check_reach(const Robot& robot, const Vector2d& p) {
  Reach r;
  const Geometry& g = robot.geometry;
  const double m = robot.limits.reach_margin;
  if (!p.allFinite()) {
    r.reason = fmt::format("target ({}, {}) is not a position: x and y must be finite numbers in mm", p.x(), p.y());
    return r;
  }
  for (int i = 0; i < kNumChains; ++i) {
    const double d = (p - g.A(i)).norm();
    const double outer = g.la_(i) + g.lb_(i) - m;
    const double inner = std::abs(g.la_(i) - g.lb_(i)) + m;
    if (d > outer || d < inner) {
      r.reason = fmt::format(
          "chain {}: target ({:.4f}, {:.4f}) is {:.4f} mm from A{}, outside its reach {:.4f} to "
          "{:.4f} mm (annulus less the {:.4g} mm margin)",
          i + 1, p.x(), p.y(), d, i + 1, inner, outer, m);
      return r;
    }
  }
  r.q = inverse_kinematics(g, p, robot.branch);
  r.cond = conditioning(g, r.q);
  if (r.cond.min_transmission < robot.limits.min_transmission) {
    int worst = 0;
    r.cond.transmission.minCoeff(&worst);
    r.reason = fmt::format(
        "target ({:.4f}, {:.4f}) is near a type-1 singularity: chain {} has |sin(theta_a - "
        "theta_b)| = {:.4f}, below the margin {:.4g}",
        p.x(), p.y(), worst + 1, r.cond.min_transmission, robot.limits.min_transmission);
    return r;
  }
  if (r.cond.direct < robot.limits.min_direct) {
    r.reason = fmt::format(
        "target ({:.4f}, {:.4f}) is near a type-2 singularity: passive-link spread {:.4f} is below "
        "the margin {:.4g}",
        p.x(), p.y(), r.cond.direct, robot.limits.min_direct);
    return r;
  }
  r.ok = true;
  return r;
}

Vector3d readings_from_active(const Geometry& g, const Vector3d& theta_a) {
  return theta_a - Vector3d(g.dth_(0), g.dth_(1), g.dth_(2));
}

Vector3d active_from_readings(const Geometry& g, const Vector3d& theta_m) {
  return theta_m + Vector3d(g.dth_(0), g.dth_(1), g.dth_(2));
}

}  // namespace gpm
