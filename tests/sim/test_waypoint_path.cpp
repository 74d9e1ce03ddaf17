// Tests of sim/waypoint_path.cpp: the path passes through every waypoint,
// starts and ends at rest, respects its speed and acceleration limits
// (checked by finite differences of the tabulated positions), matches the
// closed-form trapezoidal time law on a straight segment, the tour
// visits points on a circle in angular order, and a checked path is repaired
// with via points until every point of it passes the check (or refused).
#include "sim/waypoint_path.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <stdexcept>

#include <gtest/gtest.h>

#include "models/errors.hpp"

namespace gpm::sim {
namespace {

std::vector<Eigen::Vector2d> zigzag() {
  return {{216.5, 250.0}, {280.0, 300.0}, {180.0, 330.0}, {150.0, 220.0}, {260.0, 180.0}, {300.0, 250.0}};
}

TEST(WaypointPath, PassesThroughEveryWaypointAtItsTime) {
  const auto pts = zigzag();
  const WaypointPath path = make_waypoint_path(pts, WaypointLimits{});
  ASSERT_EQ(path.pose_times.size(), pts.size());
  for (std::size_t k = 0; k < pts.size(); ++k) {
    Eigen::Vector2d p, v;
    waypoint_at(path, path.pose_times[k], p, v);
    EXPECT_LT((p - pts[k]).norm(), 1e-9) << "waypoint " << k;
  }
  EXPECT_TRUE(std::is_sorted(path.pose_times.begin(), path.pose_times.end()));
}

TEST(WaypointPath, StartsAndEndsAtRestAndRespectsItsLimits) {
  WaypointLimits lim;
  lim.max_speed_mm_s = 120.0;
  lim.max_accel_mm_s2 = 800.0;
  lim.max_normal_mm_s2 = 600.0;
  const WaypointPath path = make_waypoint_path(zigzag(), lim, 0.05);
  Eigen::Vector2d p, v;
  waypoint_at(path, 0.0, p, v);
  EXPECT_EQ(v.norm(), 0.0);
  waypoint_at(path, waypoint_duration(path), p, v);
  EXPECT_EQ(v.norm(), 0.0);
  // Finite differences of the motion sampled at 1 kHz.
  const double dt = 1e-3;
  Eigen::Vector2d p0, p1, p2, v0;
  double worst_speed = 0, worst_tangential = 0, worst_normal = 0;
  for (double t = dt; t + dt < waypoint_duration(path); t += dt) {
    waypoint_at(path, t - dt, p0, v0);
    waypoint_at(path, t, p1, v0);
    waypoint_at(path, t + dt, p2, v0);
    const Eigen::Vector2d vel = (p2 - p0) / (2 * dt), acc = (p2 - 2 * p1 + p0) / (dt * dt);
    const double speed = vel.norm();
    worst_speed = std::max(worst_speed, speed);
    if (speed > 1.0) {
      const Eigen::Vector2d tangent = vel / speed;
      worst_tangential = std::max(worst_tangential, std::abs(acc.dot(tangent)));
      worst_normal = std::max(worst_normal, std::abs(acc.x() * tangent.y() - acc.y() * tangent.x()));
    }
  }
  EXPECT_LE(worst_speed, lim.max_speed_mm_s * 1.01);
  EXPECT_GT(worst_speed, lim.max_speed_mm_s * 0.9);  // the limit is used, not just respected
  // Piecewise-linear interpolation adds a little discretisation noise: 10 %.
  EXPECT_LE(worst_tangential, lim.max_accel_mm_s2 * 1.1);
  EXPECT_LE(worst_normal, lim.max_normal_mm_s2 * 1.1);
}

TEST(WaypointPath, StraightSegmentFollowsTheTrapezoidalTimeLaw) {
  // Two points 200 mm apart, v = 100 mm/s, a = 500 mm/s^2: ramps of 0.2 s over
  // 10 mm each, so T = L / v + v / a = 2.2 s, and the path stays on the segment.
  WaypointLimits lim;
  lim.max_speed_mm_s = 100.0;
  lim.max_accel_mm_s2 = 500.0;
  const Eigen::Vector2d a(150.0, 250.0), b(350.0, 250.0);
  const WaypointPath path = make_waypoint_path({a, b}, lim, 0.01);
  EXPECT_NEAR(path.length_mm, 200.0, 1e-6);
  EXPECT_NEAR(waypoint_duration(path), 2.2, 2e-3);
  for (const auto& q : path.p) EXPECT_NEAR(q.y(), 250.0, 1e-9);
  Eigen::Vector2d p, v;
  waypoint_at(path, 1.1, p, v);
  EXPECT_NEAR(p.x(), 250.0, 0.05);
  EXPECT_NEAR(v.x(), 100.0, 0.5);
}

TEST(WaypointPath, TourVisitsPointsOnACircleInAngularOrder) {
  const int n = 24;
  std::vector<Eigen::Vector2d> pts;
  for (int k = 0; k < n; ++k) {
    const double ang = 2 * std::numbers::pi * ((k * 7) % n) / n;  // shuffled angles
    pts.emplace_back(216.5 + 80 * std::cos(ang), 250 + 80 * std::sin(ang));
  }
  const std::vector<int> order = tour_order({296.5, 250.0}, pts);
  std::vector<int> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  std::vector<int> all(n);
  std::iota(all.begin(), all.end(), 0);
  EXPECT_EQ(sorted, all);  // a permutation
  double len = 0;
  for (int k = 1; k < n; ++k) len += (pts[order[k]] - pts[order[k - 1]]).norm();
  // The best open tour is the circle less one chord: (n - 1) chords of 2 R sin(pi / n).
  EXPECT_NEAR(len, (n - 1) * 2 * 80 * std::sin(std::numbers::pi / n), 1e-6);
}

TEST(WaypointPath, RefusesDegenerateInput) {
  EXPECT_THROW(make_waypoint_path({{0.0, 0.0}}, WaypointLimits{}), std::invalid_argument);
  EXPECT_THROW(make_waypoint_path({{0.0, 0.0}, {0.0, 0.0}}, WaypointLimits{}), std::invalid_argument);
  WaypointLimits bad;
  bad.max_speed_mm_s = 0.0;
  EXPECT_THROW(make_waypoint_path({{0.0, 0.0}, {1.0, 0.0}}, bad), std::invalid_argument);
}

// A forbidden disc astride the chord between two poses: via points take the
// path round it, and every point of the result passes the check.
TEST(WaypointPath, CheckedPathGoesRoundAForbiddenDiscThroughViaPoints) {
  const Eigen::Vector2d start(0.0, 0.0), centre(100.0, 2.0);
  const std::vector<Eigen::Vector2d> poses{{200.0, 0.0}, {200.0, 80.0}};
  const PointCheck check = [&](const Eigen::Vector2d& p) {
    return (p - centre).norm() < 20.0 ? std::string("inside the disc") : std::string();
  };
  const WaypointPath plain = excitation_path(start, poses, WaypointLimits{});
  EXPECT_TRUE(std::any_of(plain.p.begin(), plain.p.end(), [&](const auto& p) { return !check(p).empty(); }));
  PathRepair repair;
  const WaypointPath path = excitation_path(start, poses, WaypointLimits{}, check, &repair, 0.5);
  EXPECT_GE(repair.vias, 1);
  EXPECT_EQ(repair.points.size(), poses.size() + 1 + static_cast<std::size_t>(repair.vias));
  for (const Eigen::Vector2d& p : path.p) ASSERT_EQ(check(p), "") << p.transpose();
  // Still through every pose, from the start, ending at rest.
  EXPECT_LT((path.p.front() - start).norm(), 1e-9);
  for (const Eigen::Vector2d& pose : poses)
    EXPECT_TRUE(std::any_of(path.p.begin(), path.p.end(), [&](const auto& p) { return (p - pose).norm() < 1e-9; }));
  EXPECT_EQ(path.v.back().norm(), 0.0);
}

// A pose that breaks the check, or a wall no via point gets round, is
// refused (InputError, one line) before anything moves.
TEST(WaypointPath, CheckedPathRefusesABadPoseAndAnImpassableWall) {
  const Eigen::Vector2d start(0.0, 0.0);
  const PointCheck wall = [](const Eigen::Vector2d& p) {
    return std::abs(p.x() - 100.0) < 5.0 ? std::string("in the wall") : std::string();
  };
  try {
    excitation_path(start, {{200.0, 0.0}}, WaypointLimits{}, wall);
    FAIL() << "crossed the wall";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("keeps the margin"), std::string::npos) << e.what();
  }
  try {
    excitation_path(start, {{50.0, 0.0}, {100.0, 0.0}}, WaypointLimits{}, wall);
    FAIL() << "accepted a pose in the wall";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("pose 1 (100.000, 0.000) breaks the margin: in the wall"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace gpm::sim
