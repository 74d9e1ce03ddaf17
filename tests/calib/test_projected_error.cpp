// Tests of calib/projected_error.cpp (paper section 2): P is a symmetric
// idempotent projection that annihilates the eq. 11 Jacobian (eq. 15-16);
// E vanishes at the true offsets and equals 1/n sum |P_j dth_z|^2 off them
// (eq. 18-19); proposition 1 (noise in the feasible subspace leaves E
// unchanged) and proposition 2 (zero-mean noise in the infeasible subspace
// adds only its variance, eq. 28); the minimiser recovers the offsets from a
// path tracked with real (nonlinear) end-effector errors.
#include "calib/projected_error.hpp"

#include <cmath>
#include <numbers>
#include <random>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "models/kinematics.hpp"

namespace gpm::calib {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

const Vector3d kTrueOffsets(0.02, -0.015, 0.01);

std::vector<Vector2d> circle_path(int n) {  // section 2.5: a circle around home
  std::vector<Vector2d> out;
  for (int j = 0; j < n; ++j) {
    const double a = 2.0 * std::numbers::pi * j / n;
    out.emplace_back(216.5 + 40.0 * std::cos(a), 250.0 + 40.0 * std::sin(a));
  }
  return out;
}

// Readings built linearly: desired angles - true offsets + J_j v_j (a feasible
// tracking error) + extra_j.
std::vector<Vector3d> linear_readings(const Robot& m, const std::vector<Vector2d>& path,
                                      const std::vector<Vector3d>& extra) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> n01;
  std::vector<Vector3d> out;
  for (size_t j = 0; j < path.size(); ++j) {
    const JointAngles q = inverse_kinematics(m.geometry, path[j], m.branch);
    const Vector2d v(0.3 * n01(rng), 0.3 * n01(rng));
    out.push_back(q.theta_a - kTrueOffsets + active_jacobian(m.geometry, q) * v + extra[j]);
  }
  return out;
}

TEST(ProjectedError, ProjectionIsSymmetricIdempotentAndKillsTheJacobian) {
  const Robot m;
  for (const Vector2d& p : circle_path(12)) {
    const Eigen::Matrix3d P = infeasible_projection(m, p);
    const JointAngles q = inverse_kinematics(m.geometry, p, m.branch);
    EXPECT_LT((P - P.transpose()).norm(), 1e-12);
    EXPECT_LT((P * P - P).norm(), 1e-12);
    EXPECT_LT((P * active_jacobian(m.geometry, q)).norm(), 1e-12);
    EXPECT_NEAR(P.trace(), 1.0, 1e-12);  // a 1-D infeasible subspace
  }
}

TEST(ProjectedError, ZeroAtTrueOffsetsAndProjectedOffsetErrorOffThem) {
  const Robot m;
  const auto path = circle_path(24);
  const auto t = linear_readings(m, path, std::vector<Vector3d>(path.size(), Vector3d::Zero()));
  EXPECT_LT(projected_error(m, kTrueOffsets, path, t), 1e-24);
  const Vector3d dz(0.003, -0.001, 0.002);
  double expect = 0.0;
  for (const Vector2d& p : path) expect += (infeasible_projection(m, p) * dz).squaredNorm();
  expect /= static_cast<double>(path.size());
  EXPECT_NEAR(projected_error(m, kTrueOffsets + dz, path, t), expect, 1e-12 * expect);  // eq. 18-19
}

TEST(ProjectedError, Proposition1FeasibleNoiseLeavesEUnchanged) {
  const Robot m;
  const auto path = circle_path(24);
  std::mt19937_64 rng(11);
  std::normal_distribution<double> n01;
  std::vector<Vector3d> feasible;
  for (const Vector2d& p : path) {
    const JointAngles q = inverse_kinematics(m.geometry, p, m.branch);
    feasible.push_back(active_jacobian(m.geometry, q) * Vector2d(n01(rng), n01(rng)) * 0.5);
  }
  const auto clean = linear_readings(m, path, std::vector<Vector3d>(path.size(), Vector3d::Zero()));
  const auto noisy = linear_readings(m, path, feasible);
  for (const Vector3d& dz : {Vector3d(0, 0, 0), Vector3d(0.003, -0.001, 0.002), Vector3d(-0.01, 0.004, 0.0)}) {
    const double e0 = projected_error(m, kTrueOffsets + dz, path, clean);
    const double e1 = projected_error(m, kTrueOffsets + dz, path, noisy);
    EXPECT_NEAR(e1, e0, 1e-12 * std::max(e0, 1e-12));
  }
  EXPECT_LT((minimise_projected_error(m, path, noisy) - kTrueOffsets).norm(), 1e-10);
}

TEST(ProjectedError, Proposition2ZeroMeanInfeasibleNoiseAddsItsVariance) {
  const Robot m;
  const auto path = circle_path(24);
  const auto n = static_cast<Eigen::Index>(path.size());
  // Infeasible directions n_j (P_j = n_j n_j'), amplitudes a with sum a_j n_j = 0.
  Eigen::MatrixXd N(3, n);
  for (Eigen::Index j = 0; j < n; ++j) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(infeasible_projection(m, path[static_cast<size_t>(j)]));
    N.col(j) = es.eigenvectors().col(2);
  }
  std::mt19937_64 rng(5);
  std::normal_distribution<double> n01;
  Eigen::VectorXd a(n);
  for (Eigen::Index j = 0; j < n; ++j) a[j] = 1e-3 * n01(rng);
  a -= N.transpose() * (N * N.transpose()).ldlt().solve(N * a);  // zero mean (eq. 27)
  std::vector<Vector3d> delta;
  double variance = 0.0;
  for (Eigen::Index j = 0; j < n; ++j) {
    delta.push_back(a[j] * N.col(j));
    variance += delta.back().squaredNorm();
  }
  variance /= static_cast<double>(n);
  ASSERT_LT((N * a).norm(), 1e-15);
  const auto clean = linear_readings(m, path, std::vector<Vector3d>(path.size(), Vector3d::Zero()));
  const auto noisy = linear_readings(m, path, delta);
  for (const Vector3d& dz : {Vector3d(0, 0, 0), Vector3d(0.003, -0.001, 0.002)}) {
    const double e0 = projected_error(m, kTrueOffsets + dz, path, clean);
    EXPECT_NEAR(projected_error(m, kTrueOffsets + dz, path, noisy), variance + e0, 1e-12 * variance);  // eq. 28
  }
  EXPECT_LT((minimise_projected_error(m, path, noisy) - kTrueOffsets).norm(), 1e-10);
}

TEST(ProjectedError, RecoversOffsetsFromARealTrackedPath) {
  // Real motion: the robot ends up 0.1 mm off each desired point (nonlinear
  // kinematics, not the linearised model); readings = IK(real) - true offsets.
  const Robot m;
  const auto path = circle_path(36);
  std::vector<Vector3d> t;
  for (size_t j = 0; j < path.size(); ++j) {
    const double a = 0.7 * static_cast<double>(j);
    const Vector2d real = path[j] + 0.1 * Vector2d(std::cos(a), std::sin(a));
    t.push_back(inverse_kinematics(m.geometry, real, m.branch).theta_a - kTrueOffsets);
  }
  const Vector3d est = minimise_projected_error(m, path, t);
  EXPECT_LT((est - kTrueOffsets).cwiseAbs().maxCoeff(), 1e-5) << est.transpose();
  EXPECT_LT(projected_error(m, est, path, t), projected_error(m, kTrueOffsets + Vector3d(1e-3, 0, 0), path, t));
}

}  // namespace
}  // namespace gpm::calib
