// Continuous excitation path through poses (sim/waypoint_path.hpp).
#include "sim/waypoint_path.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>

#include "models/errors.hpp"

namespace gpm::sim {
namespace {

// Centripetal Catmull-Rom point on the segment P1 -> P2 (Barry-Goldman
// pyramidal form with knot spacing |P_{k+1} - P_k|^(1/2)), u in [0, 1].
Eigen::Vector2d catmull_rom(const Eigen::Vector2d& P0, const Eigen::Vector2d& P1, const Eigen::Vector2d& P2,
                            const Eigen::Vector2d& P3, double u) {
  auto knot = [](double t, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return t + std::sqrt(std::max((b - a).norm(), 1e-9));
  };
  const double t0 = 0.0, t1 = knot(t0, P0, P1), t2 = knot(t1, P1, P2), t3 = knot(t2, P2, P3);
  const double t = t1 + u * (t2 - t1);
  const Eigen::Vector2d A1 = (t1 - t) / (t1 - t0) * P0 + (t - t0) / (t1 - t0) * P1;
  const Eigen::Vector2d A2 = (t2 - t) / (t2 - t1) * P1 + (t - t1) / (t2 - t1) * P2;
  const Eigen::Vector2d A3 = (t3 - t) / (t3 - t2) * P2 + (t - t2) / (t3 - t2) * P3;
  const Eigen::Vector2d B1 = (t2 - t) / (t2 - t0) * A1 + (t - t0) / (t2 - t0) * A2;
  const Eigen::Vector2d B2 = (t3 - t) / (t3 - t1) * A2 + (t - t1) / (t3 - t1) * A3;
  return (t2 - t) / (t2 - t1) * B1 + (t - t1) / (t2 - t1) * B2;
}

// Curvature of the circle through three consecutive nodes (1 / circumradius).
double curvature(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const double ab = (b - a).norm(), bc = (c - b).norm(), ca = (a - c).norm();
  const Eigen::Vector2d u = b - a, w = c - a;
  const double cross2 = std::abs(u.x() * w.y() - u.y() * w.x());  // twice the triangle area
  const double denom = ab * bc * ca;
  return denom > 0.0 ? 2.0 * cross2 / denom : 0.0;
}

// Why some point of the straight line a -> b (every step mm, ends included)
// breaks check; empty when none does.
std::string chord_violation(const PointCheck& check, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                            double step) {
  const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step)));
  for (int s = 0; s <= n; ++s) {
    std::string why = check(a + (b - a) * (static_cast<double>(s) / n));
    if (!why.empty()) return why;
  }
  return {};
}

}  // namespace

std::vector<int> tour_order(const Eigen::Vector2d& start, const std::vector<Eigen::Vector2d>& poses) {
  const int n = static_cast<int>(poses.size());
  std::vector<int> order;
  std::vector<bool> used(n, false);
  Eigen::Vector2d at = start;
  for (int k = 0; k < n; ++k) {
    int best = -1;
    double dbest = std::numeric_limits<double>::infinity();
    for (int j = 0; j < n; ++j)
      if (!used[j] && (poses[j] - at).norm() < dbest) dbest = (poses[j] - at).norm(), best = j;
    used[best] = true;
    order.push_back(best);
    at = poses[best];
  }
  // 2-opt on the open tour start -> order[0] -> ... -> order[n-1]: reverse
  // order[i..j] when that shortens it; repeat until no reversal helps.
  for (bool improved = true; improved;) {
    improved = false;
    for (int i = 0; i < n - 1; ++i) {
      for (int j = i + 1; j < n; ++j) {
        const Eigen::Vector2d& before = i == 0 ? start : poses[order[i - 1]];
        const double old_len = (poses[order[i]] - before).norm() +
                               (j + 1 < n ? (poses[order[j + 1]] - poses[order[j]]).norm() : 0.0);
        const double new_len = (poses[order[j]] - before).norm() +
                               (j + 1 < n ? (poses[order[j + 1]] - poses[order[i]]).norm() : 0.0);
        if (new_len < old_len - 1e-9) {
          std::reverse(order.begin() + i, order.begin() + j + 1);
          improved = true;
        }
      }
    }
  }
  return order;
}

WaypointPath make_waypoint_path(const std::vector<Eigen::Vector2d>& points, const WaypointLimits& limits,
                                double step_mm) {
  const int n = static_cast<int>(points.size());
  if (n < 2) throw std::invalid_argument("waypoint path: need at least two points");
  if (!(limits.max_speed_mm_s > 0.0 && limits.max_accel_mm_s2 > 0.0 && limits.max_normal_mm_s2 > 0.0 &&
        step_mm > 0.0))
    throw std::invalid_argument("waypoint path: limits and step must be positive");
  for (int k = 1; k < n; ++k)
    if ((points[k] - points[k - 1]).norm() < 1e-6)
      throw std::invalid_argument("waypoint path: consecutive points coincide");

  // Dense polyline along the spline; phantom end points mirror the ends.
  WaypointPath out;
  std::vector<int> pose_node(n, 0);
  out.p.push_back(points[0]);
  for (int k = 0; k + 1 < n; ++k) {
    const Eigen::Vector2d P0 = k > 0 ? points[k - 1] : Eigen::Vector2d(2.0 * points[0] - points[1]);
    const Eigen::Vector2d P3 = k + 2 < n ? points[k + 2] : Eigen::Vector2d(2.0 * points[n - 1] - points[n - 2]);
    // Subdivide finely enough that chords are about step_mm (the spline is at
    // most a few times longer than its chord).
    const int m = std::max(4, static_cast<int>(std::ceil(3.0 * (points[k + 1] - points[k]).norm() / step_mm)));
    for (int s = 1; s <= m; ++s) out.p.push_back(catmull_rom(P0, points[k], points[k + 1], P3, double(s) / m));
    pose_node[k + 1] = static_cast<int>(out.p.size()) - 1;
  }
  const int N = static_cast<int>(out.p.size());
  std::vector<double> ds(N, 0.0), vlim(N, limits.max_speed_mm_s);
  for (int i = 1; i < N; ++i) {
    ds[i] = (out.p[i] - out.p[i - 1]).norm();
    out.length_mm += ds[i];
  }
  for (int i = 1; i + 1 < N; ++i) {
    const double kappa = curvature(out.p[i - 1], out.p[i], out.p[i + 1]);
    if (kappa > 0.0) vlim[i] = std::min(vlim[i], std::sqrt(limits.max_normal_mm_s2 / kappa));
  }
  vlim.front() = vlim.back() = 0.0;
  // Forward and backward passes with the tangential acceleration limit.
  std::vector<double> speed = vlim;
  for (int i = 1; i < N; ++i)
    speed[i] = std::min(speed[i], std::sqrt(speed[i - 1] * speed[i - 1] + 2.0 * limits.max_accel_mm_s2 * ds[i]));
  for (int i = N - 2; i >= 0; --i)
    speed[i] = std::min(speed[i], std::sqrt(speed[i + 1] * speed[i + 1] + 2.0 * limits.max_accel_mm_s2 * ds[i + 1]));
  // Time at each node: ds over the mean speed of the step.
  out.t.assign(N, 0.0);
  out.v.assign(N, Eigen::Vector2d::Zero());
  for (int i = 1; i < N; ++i) {
    const double mean = 0.5 * (speed[i - 1] + speed[i]);
    out.t[i] = out.t[i - 1] + (mean > 0.0 ? ds[i] / mean : 0.0);
  }
  for (int i = 0; i < N; ++i) {
    const int a = std::max(0, i - 1), b = std::min(N - 1, i + 1);
    const Eigen::Vector2d d = out.p[b] - out.p[a];
    if (d.norm() > 0.0) out.v[i] = speed[i] * d.normalized();
  }
  for (int k = 0; k < n; ++k) out.pose_times.push_back(out.t[pose_node[k]]);
  return out;
}

WaypointPath excitation_path(const Eigen::Vector2d& start, const std::vector<Eigen::Vector2d>& poses,
                             const WaypointLimits& limits) {
  std::vector<Eigen::Vector2d> points{start};
  for (int k : tour_order(start, poses))
    if ((poses[static_cast<std::size_t>(k)] - points.back()).norm() > 1e-6) points.push_back(poses[static_cast<std::size_t>(k)]);
  return make_waypoint_path(points, limits);
}

WaypointPath excitation_path(const Eigen::Vector2d& start, const std::vector<Eigen::Vector2d>& poses,
                             const WaypointLimits& limits, const PointCheck& check, PathRepair* repair,
                             double check_mm) {
  if (!check) return excitation_path(start, poses, limits);
  if (const std::string why = check(start); !why.empty())
    throw InputError(fmt::format("the path's start ({:.3f}, {:.3f}) breaks the margin: {}", start.x(), start.y(), why));
  for (std::size_t k = 0; k < poses.size(); ++k)
    if (const std::string why = check(poses[k]); !why.empty())
      throw InputError(fmt::format("pose {} ({:.3f}, {:.3f}) breaks the margin: {}", k, poses[k].x(), poses[k].y(), why));
  std::vector<Eigen::Vector2d> points{start};
  for (int k : tour_order(start, poses))
    if ((poses[static_cast<std::size_t>(k)] - points.back()).norm() > 1e-6) points.push_back(poses[static_cast<std::size_t>(k)]);
  int vias = 0;
  std::size_t from_point = 0;  // segments before this point are unchanged since they were checked
  for (;;) {
    WaypointPath path = make_waypoint_path(points, limits);
    const double t_from = path.pose_times[from_point];
    std::size_t bad = path.p.size();
    std::string why;
    double since = INFINITY;
    for (std::size_t k = 0; k < path.p.size(); ++k) {
      if (path.t[k] < t_from) continue;
      since += k > 0 ? (path.p[k] - path.p[k - 1]).norm() : 0.0;
      if (since < check_mm && k + 1 < path.p.size()) continue;
      since = 0.0;
      why = check(path.p[k]);
      if (!why.empty()) {
        bad = k;
        break;
      }
    }
    if (bad == path.p.size()) {
      if (repair) repair->vias = vias, repair->points = points;
      return path;
    }
    // The segment points[seg] -> points[seg + 1] holding the bad point.
    const auto it = std::upper_bound(path.pose_times.begin(), path.pose_times.end(), path.t[bad]);
    const std::size_t seg =
        std::min(points.size() - 2, static_cast<std::size_t>(std::max<std::ptrdiff_t>(0, it - path.pose_times.begin() - 1)));
    const Eigen::Vector2d a = points[seg], b = points[seg + 1];
    const auto refuse = [&](const std::string& reason) {
      return InputError(fmt::format("no path from ({:.3f}, {:.3f}) to ({:.3f}, {:.3f}) keeps the margin ({}): at "
                                    "t = {:.3f} s {}",
                                    a.x(), a.y(), b.x(), b.y(), reason, path.t[bad], why));
    };
    if ((b - a).norm() < 4.0 * check_mm || vias >= 20 * static_cast<int>(poses.size()) + 20)
      throw refuse("via points do not help");
    // A via point: the chord's midpoint, else points off the chord on either side.
    const Eigen::Vector2d mid = 0.5 * (a + b);
    const Eigen::Vector2d normal = Eigen::Vector2d(a.y() - b.y(), b.x() - a.x()).normalized();
    std::optional<Eigen::Vector2d> via;
    for (int step = 0; step <= 30 && !via; ++step) {
      for (int side : {1, -1}) {
        const Eigen::Vector2d v = mid + side * 5.0 * step * normal;
        if (check(v).empty() && chord_violation(check, a, v, check_mm).empty() &&
            chord_violation(check, v, b, check_mm).empty()) {
          via = v;
          break;
        }
        if (step == 0) break;
      }
    }
    if (!via) throw refuse("no via point within 150 mm of the chord");
    points.insert(points.begin() + static_cast<std::ptrdiff_t>(seg) + 1, *via);
    ++vias;
    from_point = seg > 0 ? seg - 1 : 0;
  }
}

void waypoint_at(const WaypointPath& path, double t, Eigen::Vector2d& p, Eigen::Vector2d& v) {
  if (path.t.empty()) {
    p.setZero();
    v.setZero();
    return;
  }
  if (t <= 0.0) {
    p = path.p.front();
    v.setZero();
    return;
  }
  if (t >= path.t.back()) {
    p = path.p.back();
    v.setZero();
    return;
  }
  const auto it = std::upper_bound(path.t.begin(), path.t.end(), t);
  const std::size_t i = static_cast<std::size_t>(it - path.t.begin());  // path.t[i-1] <= t < path.t[i]
  // Constant tangential acceleration within a step: arc s(tau) = v0 tau +
  // (v1 - v0) tau^2 / (2 h), which covers the step exactly at tau = h
  // because h = 2 ds / (v0 + v1).
  const double h = path.t[i] - path.t[i - 1];
  const double tau = t - path.t[i - 1];
  const double v0 = path.v[i - 1].norm(), v1 = path.v[i].norm();
  const double ds = (path.p[i] - path.p[i - 1]).norm();
  const double arc = h > 0.0 ? v0 * tau + 0.5 * (v1 - v0) * tau * tau / h : ds;
  const double u = ds > 0.0 ? std::clamp(arc / ds, 0.0, 1.0) : 1.0;
  p = (1.0 - u) * path.p[i - 1] + u * path.p[i];
  const double speed = h > 0.0 ? v0 + (v1 - v0) * tau / h : v1;
  v = ds > 0.0 ? Eigen::Vector2d(speed * (path.p[i] - path.p[i - 1]) / ds) : Eigen::Vector2d::Zero();
}

}  // namespace gpm::sim
