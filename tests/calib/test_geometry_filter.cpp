// Tests of calib/geometry_filter.cpp: the filter of the geometry on
// the closure residual finds a robot's geometry from exact readings along a
// path (hand-made truth), agrees with the batch maximum a posteriori fit of
// the same residual and prior (Gauss-Newton on all samples at once), moves
// the estimate only along what one sample sees, holds the frame, and keeps
// a covariance that shrinks as samples come.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include <Eigen/Dense>

#include "calib/geometry_filter.hpp"
#include "calib/residuals.hpp"
#include "models/kinematics.hpp"

namespace gpm::calib {
namespace {

// A robot whose encoders' zeros are off by a few hundredths of a radian and
// whose links and third base differ by tenths of a millimetre.
Geometry robot_off_its_data_sheet() {
  Geometry g = Geometry::gpm2002_nominal();
  g[dth(0)] = 0.012;
  g[dth(1)] = -0.021;
  g[dth(2)] = 0.017;
  g[la(1)] += 0.4;
  g[lb(2)] -= 0.3;
  g[kXa3] += 0.2;
  return g;
}

// Exact readings of g along a lemniscate round home (two lobes, 400 points).
std::vector<Eigen::Vector3d> readings_along_path(const Geometry& g, int n = 400) {
  std::vector<Eigen::Vector3d> out;
  for (int k = 0; k < n; ++k) {
    const double s = 2.0 * std::numbers::pi * k / n;
    const Eigen::Vector2d p(216.5 + 90.0 * std::sin(s), 250.0 + 60.0 * std::sin(2.0 * s));
    out.push_back(readings_from_active(g, inverse_kinematics(g, p).theta_a));
  }
  return out;
}

// The ML residual r = P / |dP/d theta_m| of one sample under g (the filter's measurement).
double ml_residual(const Geometry& g, const Eigen::Vector3d& theta_m) {
  double r = 0.0;
  EXPECT_TRUE(MlResidual(theta_m)(g.values.data(), &r));
  return r;
}

// dr/dx over the filter's free parameters by central differences.
Eigen::RowVectorXd residual_jacobian(const Geometry& g, const Eigen::Vector3d& m, const std::vector<int>& free) {
  Eigen::RowVectorXd J(static_cast<Eigen::Index>(free.size()));
  for (std::size_t k = 0; k < free.size(); ++k) {
    Geometry plus = g, minus = g;
    plus[free[k]] += 1e-6;
    minus[free[k]] -= 1e-6;
    J[static_cast<Eigen::Index>(k)] = (ml_residual(plus, m) - ml_residual(minus, m)) / 2e-6;
  }
  return J;
}

// What the offsets stage needs of the filter: where the readings put the
// end-effector. Exact readings along the path, the data sheet's geometry
// against the one learnt from them (and the truth).
TEST(GeometryFilter, ExactReadingsLocateTheEndEffectorFarBetterThanTheDataSheet) {
  const Geometry truth = robot_off_its_data_sheet();
  GeometryFilterSettings exact;
  exact.misfit_sigma_rad = 1e-4;  // the readings close the loops; a small misfit keeps each step linear
  GeometryFilter filter(Geometry::gpm2002_nominal(), exact);
  const std::vector<Eigen::Vector3d> readings = readings_along_path(truth);
  for (const Eigen::Vector3d& m : readings) filter.update(m);
  EXPECT_EQ(filter.updates(), 400);
  EXPECT_EQ(filter.free_index().size(), 11u);
  const auto located = [&](const Geometry& g, const Eigen::Vector3d& m) {
    return forward_kinematics(g, active_from_readings(g, m))->p;
  };
  double stated = 0.0, learnt = 0.0;
  for (const Eigen::Vector3d& m : readings) {
    const Eigen::Vector2d p = located(truth, m);
    stated = std::max(stated, (located(Geometry::gpm2002_nominal(), m) - p).norm());
    learnt = std::max(learnt, (located(filter.geometry(), m) - p).norm());
  }
  std::printf("end-effector from the readings, worst over the path: data sheet %.3f mm, learnt %.3f mm\n", stated,
              learnt);
  EXPECT_GT(stated, 3.0);
  EXPECT_LT(learnt, 0.1 * stated);
}

TEST(GeometryFilter, AgreesWithTheBatchFitOfTheSameResidualAndPrior) {
  // Readings of the robot through a drive train that twists a little with
  // the path: no geometry closes every loop, so filter and batch meet at
  // the same compromise.
  std::vector<Eigen::Vector3d> readings = readings_along_path(robot_off_its_data_sheet(), 300);
  for (std::size_t k = 0; k < readings.size(); ++k) readings[k][1] += 4e-4 * std::sin(0.05 * static_cast<double>(k));
  const GeometryFilterSettings settings;
  GeometryFilter filter(Geometry::gpm2002_nominal(), settings);
  for (const Eigen::Vector3d& m : readings) filter.update(m);
  // Gauss-Newton on sum (r_k / sigma_r)^2 + (x - x0)^T Sigma0^-1 (x - x0).
  const std::vector<int>& free = filter.free_index();
  const auto n = static_cast<Eigen::Index>(free.size());
  const Geometry start = Geometry::gpm2002_nominal();
  const Eigen::MatrixXd prior_info = GeometryFilter(start, settings).covariance().inverse();
  Geometry batch = start;
  for (int iteration = 0; iteration < 10; ++iteration) {
    Eigen::VectorXd x_minus_x0(n);
    for (Eigen::Index k = 0; k < n; ++k) x_minus_x0[k] = batch[free[k]] - start[free[k]];
    Eigen::MatrixXd A = prior_info;
    Eigen::VectorXd b = -prior_info * x_minus_x0;
    const double w = 1.0 / std::pow(settings.misfit_sigma_rad, 2);
    for (const Eigen::Vector3d& m : readings) {
      const Eigen::RowVectorXd J = residual_jacobian(batch, m, free);
      A += w * J.transpose() * J;
      b -= w * J.transpose() * ml_residual(batch, m);
    }
    const Eigen::VectorXd step = A.ldlt().solve(b);
    for (Eigen::Index k = 0; k < n; ++k) batch[free[k]] += step[k];
  }
  for (int p : free)
    EXPECT_NEAR(filter.geometry()[p], batch[p], is_offset(p) ? 1e-3 : 0.1) << param_name(p);  // a twentieth of the prior
}

TEST(GeometryFilter, OneSampleMovesTheEstimateOnlyAlongWhatItSeesAndHoldsTheFrame) {
  const Eigen::Vector3d m = readings_along_path(robot_off_its_data_sheet(), 8)[1];
  const Geometry nominal = Geometry::gpm2002_nominal();
  const GeometryFilterSettings settings;
  GeometryFilter filter(nominal, settings);
  const Eigen::MatrixXd prior = filter.covariance();
  filter.update(m);
  const std::vector<int>& free = filter.free_index();
  const auto n = static_cast<Eigen::Index>(free.size());
  Eigen::VectorXd change(n);
  for (Eigen::Index k = 0; k < n; ++k) change[k] = filter.geometry()[free[k]] - nominal[free[k]];
  // The change lies along Sigma0 H^T (the gain's direction).
  const Eigen::RowVectorXd H = residual_jacobian(nominal, m, free);
  const Eigen::VectorXd gain = prior * H.transpose();
  EXPECT_GT(change.norm(), 1e-4);
  EXPECT_NEAR(std::abs(change.normalized().dot(gain.normalized())), 1.0, 1e-6);
  // Below one sample's misfit where it sees; untouched where H Sigma0 u = 0.
  EXPECT_LT(H * filter.covariance() * H.transpose(), std::pow(settings.misfit_sigma_rad, 2));
  Eigen::VectorXd u = Eigen::VectorXd::Ones(n);
  u -= (H.dot(prior * u) / H.dot(gain)) * H.transpose();
  EXPECT_NEAR(u.dot(filter.covariance() * u), u.dot(prior * u), 1e-9 * u.dot(prior * u));
  for (int p : {kXa1, kYa1, kXa2, kYa2}) EXPECT_EQ(filter.geometry()[p], nominal[p]) << param_name(p);
}

TEST(GeometryFilter, CovarianceShrinksAsSamplesComeAndStaysSymmetricPositive) {
  GeometryFilter filter(Geometry::gpm2002_nominal());
  double last = filter.covariance().trace();
  for (const Eigen::Vector3d& m : readings_along_path(robot_off_its_data_sheet(), 200)) {
    filter.update(m);
    EXPECT_LE(filter.covariance().trace(), last * (1.0 + 1e-12));
    last = filter.covariance().trace();
  }
  const Eigen::MatrixXd& S = filter.covariance();
  EXPECT_LT((S - S.transpose()).norm(), 1e-12 * S.norm());
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(S).eigenvalues().minCoeff(), 0.0);
}

}  // namespace
}  // namespace gpm::calib
