// Tests of sim/trajectory.cpp: path positions against closed forms, path
// velocities against central differences, move boundary conditions and peak
// speed, and the pose generators.
#include "sim/trajectory.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace gpm::sim {
namespace {

using Eigen::Vector2d;

void expect_velocity_is_derivative(const Path& path) {
  const double h = 1e-6, T = path_duration(path);
  for (int k = 1; k < 50; ++k) {
    const double t = T * k / 50.0;
    const Vector2d fd = (path_at(path, t + h).p - path_at(path, t - h).p) / (2 * h);
    EXPECT_LT((fd - path_at(path, t).v).norm(), 1e-4 * (1.0 + fd.norm())) << "t = " << t;
  }
}

TEST(Trajectory, CircleStartsOnTheRightAndKeepsItsRadius) {
  const CirclePath c{{216.5, 250.0}, 50.0, 2.0, 1.5};
  EXPECT_DOUBLE_EQ(path_duration(c), 3.0);
  EXPECT_LT((path_at(c, 0.0).p - Vector2d(266.5, 250.0)).norm(), 1e-12);
  EXPECT_LT((path_at(c, 0.5).p - Vector2d(216.5, 300.0)).norm(), 1e-12);  // a quarter turn, ccw
  for (double t = 0; t < 3.0; t += 0.1) EXPECT_NEAR((path_at(c, t).p - c.centre).norm(), 50.0, 1e-12);
  EXPECT_NEAR(path_at(c, 0.3).v.norm(), 2 * std::numbers::pi * 50.0 / 2.0, 1e-9);
  expect_velocity_is_derivative(c);
}

TEST(Trajectory, LineIsConstantSpeed) {
  const LinePath l{{0, 0}, {30, 40}, 2.0};
  EXPECT_LT((path_at(l, 1.0).p - Vector2d(15, 20)).norm(), 1e-12);
  EXPECT_LT((path_at(l, 0.4).v - Vector2d(15, 20)).norm(), 1e-12);
  expect_velocity_is_derivative(l);
}

TEST(Trajectory, MoveStartsAndEndsAtRestWithTheRequestedPeakSpeed) {
  const MovePath m = make_move({0, 0}, {60, 80}, 100.0);
  EXPECT_NEAR(m.duration_s, 1.875, 1e-12);  // 1.875 * 100 mm / 100 mm/s
  EXPECT_LT((path_at(m, 0.0).p - Vector2d(0, 0)).norm(), 1e-12);
  EXPECT_LT((path_at(m, m.duration_s).p - Vector2d(60, 80)).norm(), 1e-12);
  EXPECT_LT(path_at(m, 0.0).v.norm(), 1e-12);
  EXPECT_LT(path_at(m, m.duration_s).v.norm(), 1e-12);
  EXPECT_NEAR(path_at(m, 0.5 * m.duration_s).v.norm(), 100.0, 1e-9);
  expect_velocity_is_derivative(m);
  // After the end: at the target, at rest.
  EXPECT_LT((path_at(m, 10.0).p - Vector2d(60, 80)).norm(), 1e-12);
  EXPECT_EQ(path_at(m, 10.0).v.norm(), 0.0);
  // A zero-length move still lasts the minimum duration.
  EXPECT_DOUBLE_EQ(make_move({1, 1}, {1, 1}, 100.0).duration_s, 0.05);
}

TEST(Trajectory, DiscPosesAreInsideUniformAndSeeded) {
  Rng a(5), b(5);
  const auto p = disc_poses({216.5, 250.0}, 60.0, 4000, a);
  EXPECT_EQ(p, disc_poses({216.5, 250.0}, 60.0, 4000, b));
  int inner = 0;
  Vector2d mean = Vector2d::Zero();
  for (const auto& x : p) {
    const double r = (x - Vector2d(216.5, 250.0)).norm();
    ASSERT_LE(r, 60.0);
    inner += r < 30.0 ? 1 : 0;
    mean += x / p.size();
  }
  // Uniform over the area: a quarter of the poses within half the radius.
  EXPECT_NEAR(inner / 4000.0, 0.25, 0.03);
  EXPECT_LT((mean - Vector2d(216.5, 250.0)).norm(), 2.0);
}

}  // namespace
}  // namespace gpm::sim
