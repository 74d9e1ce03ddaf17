#include "sim/trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gpm::sim {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

PathPoint at(const CirclePath& c, double t) {
  const double w = kTwoPi / c.period_s;
  const double a = w * t;
  PathPoint out;
  out.p = c.centre + c.radius * Eigen::Vector2d(std::cos(a), std::sin(a));
  out.v = c.radius * w * Eigen::Vector2d(-std::sin(a), std::cos(a));
  return out;
}

PathPoint at(const LinePath& l, double t) {
  const double u = l.duration_s > 0.0 ? t / l.duration_s : 1.0;
  PathPoint out;
  out.p = l.from + u * (l.to - l.from);
  out.v = l.duration_s > 0.0 ? Eigen::Vector2d((l.to - l.from) / l.duration_s)
                             : Eigen::Vector2d::Zero();
  return out;
}

PathPoint at(const MovePath& m, double t) {
  PathPoint out;
  if (!(m.duration_s > 0.0)) {
    out.p = m.to;
    return out;
  }
  const double u = t / m.duration_s;
  const double s = u * u * u * (10.0 - 15.0 * u + 6.0 * u * u);
  const double ds = 30.0 * u * u * (1.0 - u) * (1.0 - u) / m.duration_s;
  out.p = m.from + s * (m.to - m.from);
  out.v = ds * (m.to - m.from);
  return out;
}

}  // namespace

double path_duration(const Path& path) {
  return std::visit(
      [](const auto& p) -> double {
        using T = std::decay_t<decltype(p)>;
        if constexpr (std::is_same_v<T, CirclePath>) return p.period_s * p.revolutions;
        else return p.duration_s;
      },
      path);
}

PathPoint path_at(const Path& path, double t) {
  const double tc = std::clamp(t, 0.0, path_duration(path));
  PathPoint out = std::visit([tc](const auto& p) { return at(p, tc); }, path);
  if (t > path_duration(path)) out.v.setZero();
  return out;
}

MovePath make_move(const Eigen::Vector2d& from, const Eigen::Vector2d& to, double max_speed_mm_s,
                   double min_duration_s) {
  const double length = (to - from).norm();
  return MovePath{from, to, std::max(min_duration_s, 1.875 * length / max_speed_mm_s)};
}

std::vector<Eigen::Vector2d> disc_poses(const Eigen::Vector2d& centre, double radius, int count,
                                        Rng& rng) {
  std::vector<Eigen::Vector2d> out;
  for (int k = 0; k < count; ++k) {
    const double r = radius * std::sqrt(rng.uniform());
    const double a = kTwoPi * rng.uniform();
    out.push_back(centre + r * Eigen::Vector2d(std::cos(a), std::sin(a)));
  }
  return out;
}

}  // namespace gpm::sim
