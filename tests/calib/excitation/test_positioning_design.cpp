// Tests of calib/excitation/positioning_design.hpp: the error's columns are
// the offsets' columns weighed by the reading's sine and cosine, the weight
// gives the positioning error's mean square (against calib/positioning_error),
// the bound tends to the geometry's own as the prior shrinks (against
// fisher.hpp's information), the exchange ends where no single swap helps,
// and design_poses with the criterion beats the worst design on it.
#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "calib/excitation/candidates.hpp"
#include "calib/excitation/excitation.hpp"
#include "calib/excitation/fisher.hpp"
#include "calib/excitation/positioning_design.hpp"
#include "calib/positioning_error.hpp"
#include "models/errors.hpp"
#include "models/kinematics.hpp"

namespace gpm::calib::excitation {
namespace {

std::vector<Eigen::Vector2d> grid_poses(const Robot& robot, double step) {
  return reachable_grid(robot, step, Guard{});
}

PositioningPrior prior_of(double s) {
  PositioningPrior p;
  p.cyclic_prior_rad = s;
  return p;
}

std::vector<int> first(int n) {
  std::vector<int> v(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) v[static_cast<size_t>(k)] = k;
  return v;
}

// The reading carries e = a sin(theta_m) + b cos(theta_m); theta_a = theta_m
// + dth - e, so at each pose a acts as the offset change -sin(theta_m) a.
TEST(PositioningDesign, ErrorColumnsAreTheOffsetsWeighedByTheReading) {
  const Robot robot;
  const FreeMask free = default_free_mask();
  const std::vector<Eigen::Vector2d> poses = {robot.home, robot.home + Eigen::Vector2d(40, -30),
                                              robot.home + Eigen::Vector2d(-50, 20)};
  const Eigen::MatrixXd rows = information_rows(robot, free, poses);
  const Eigen::MatrixXd with = rows_with_cyclic_error(robot, free, poses);
  ASSERT_EQ(with.cols(), rows.cols() + 6);
  EXPECT_TRUE(with.leftCols(rows.cols()).isApprox(rows));
  int col = 0;
  std::array<int, 3> dth_col{};
  for (int k = 0; k < kNumParams; ++k)
    if (free.test(static_cast<size_t>(k))) {
      for (int i = 0; i < 3; ++i)
        if (k == dth(i)) dth_col[static_cast<size_t>(i)] = col;
      ++col;
    }
  for (size_t j = 0; j < poses.size(); ++j) {
    const Eigen::Vector3d theta_m =
        readings_from_active(robot.geometry, inverse_kinematics(robot.geometry, poses[j], robot.branch).theta_a);
    const auto r = static_cast<Eigen::Index>(j);
    for (int i = 0; i < 3; ++i) {
      const double g = rows(r, dth_col[static_cast<size_t>(i)]);
      EXPECT_NEAR(with(r, rows.cols() + 2 * i), -std::sin(theta_m[i]) * g, 1e-12 * std::abs(g) + 1e-15);
      EXPECT_NEAR(with(r, rows.cols() + 2 * i + 1), -std::cos(theta_m[i]) * g, 1e-12 * std::abs(g) + 1e-15);
    }
  }
}

TEST(PositioningDesign, WeightGivesThePositioningErrorsMeanSquare) {
  const Robot robot;
  const WorkspaceDisc disc{robot.home, 40.0, 10.0};
  const Eigen::Matrix<double, kNumParams, kNumParams> W = positioning_weight(robot, disc);
  // A covariance of some spread over every parameter, correlated.
  Eigen::Matrix<double, kNumParams, kNumParams> A = Eigen::Matrix<double, kNumParams, kNumParams>::Random() * 1e-3;
  const Eigen::Matrix<double, kNumParams, kNumParams> C = A * A.transpose();
  const PositioningError e = positioning_error(robot, robot, disc, C);
  // trace(W C) = mean trace(J C J') = 2 (stated 1-sigma per axis)^2, in mm^2.
  EXPECT_NEAR(std::sqrt((W * C).trace()) * 1e3, std::sqrt(2.0) * e.stated_sigma_rms_um, 1e-9 * e.stated_sigma_rms_um);
  EXPECT_THROW(positioning_weight(robot, WorkspaceDisc{{5000.0, 5000.0}, 10.0, 5.0}), InputError);
}

TEST(PositioningDesign, BoundTendsToTheGeometrysOwnAsThePriorShrinks) {
  const Robot robot;
  const FreeMask free = default_free_mask();
  const std::vector<Eigen::Vector2d> poses = grid_poses(robot, 40.0);
  ASSERT_GE(poses.size(), 20u);
  const Eigen::MatrixXd rows = rows_with_cyclic_error(robot, free, poses);
  const double sigma = 1e-5;
  // The geometry alone: C = sigma^2 / n (rows' rows)^-1 (fisher.hpp), trace(W C).
  const PositioningPrior tiny = prior_of(1e-12);
  const Eigen::MatrixXd geo = information_rows(robot, free, poses);
  const Eigen::MatrixXd C = fisher_information(geo, sigma / std::sqrt(tiny.samples_per_pose)).inverse();
  const Eigen::Matrix<double, kNumParams, kNumParams> W15 =
      positioning_weight(robot, WorkspaceDisc{robot.home, tiny.radius_mm, tiny.step_mm});
  double trace = 0.0;
  std::vector<int> index;
  for (int k = 0; k < kNumParams; ++k)
    if (free.test(static_cast<size_t>(k))) index.push_back(k);
  for (size_t a = 0; a < index.size(); ++a)
    for (size_t b = 0; b < index.size(); ++b)
      trace += W15(index[a], index[b]) * C(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b));
  const double geometry_um = std::sqrt(trace) * 1e3;
  const std::vector<int> all = first(static_cast<int>(poses.size()));
  const auto bound = [&](double s) {
    return positioning_bound_um(rows, all, positioning_criterion(robot, free, prior_of(s), sigma, rows));
  };
  EXPECT_NEAR(bound(1e-12), geometry_um, 1e-6 * geometry_um);
  // A wider prior can only cost: the bound grows with it.
  EXPECT_LT(bound(1e-12), bound(1e-5));
  EXPECT_LT(bound(1e-5), bound(1e-4));
  // No prior given: the data sheet's, as the calibration's.
  EXPECT_DOUBLE_EQ(bound(0.0), bound(robot.data_sheet.joint_harmonic_max_rad() / std::sqrt(2.0)));
  Robot exact = robot;
  exact.data_sheet.encoder_accuracy_rad.nominal = exact.data_sheet.transmission_error_rad.nominal = 0.0;
  EXPECT_THROW(positioning_criterion(exact, free, prior_of(0.0), sigma, rows), InputError);
}

TEST(PositioningDesign, ExchangeEndsWhereNoSingleSwapHelps) {
  const Robot robot;
  const FreeMask free = default_free_mask();
  const std::vector<Eigen::Vector2d> cand = grid_poses(robot, 30.0);
  const Eigen::MatrixXd rows = rows_with_cyclic_error(robot, free, cand);
  const PositioningCriterion c = positioning_criterion(robot, free, prior_of(2e-5), 1e-5, rows);
  std::vector<int> chosen = first(15);
  const double start = positioning_bound_um(rows, chosen, c);
  ASSERT_TRUE(std::isfinite(start));
  const int swaps = exchange_positioning(rows, chosen, c, 1000);
  const double end = positioning_bound_um(rows, chosen, c);
  EXPECT_GT(swaps, 0);
  EXPECT_LT(end, start);
  // Every single swap, priced from scratch, is no better.
  for (size_t s = 0; s < chosen.size(); ++s)
    for (int j = 0; j < static_cast<int>(cand.size()); ++j) {
      if (std::find(chosen.begin(), chosen.end(), j) != chosen.end()) continue;
      std::vector<int> t = chosen;
      t[s] = j;
      ASSERT_GE(positioning_bound_um(rows, t, c), end * (1.0 - 1e-6)) << "swap " << s << " -> " << j;
    }
}

TEST(PositioningDesign, DesignBeatsTheWorstDesignOnTheCriterion) {
  const Robot robot;
  DesignOptions o;
  o.count = 20;
  o.grid_step_mm = 10.0;
  o.sigma = 1e-5;
  const Design worst = design_poses(robot, o);
  o.criterion = Criterion::kPositioning;
  o.positioning = prior_of(2e-5);
  const Design pos = design_poses(robot, o);
  ASSERT_EQ(pos.poses.size(), 20u);
  for (const Eigen::Vector2d& p : pos.poses) EXPECT_TRUE(check_reach(robot, p).ok);
  const auto bound_of = [&](const std::vector<Eigen::Vector2d>& poses) {
    const Eigen::MatrixXd rows = rows_with_cyclic_error(robot, o.free, poses);
    return positioning_bound_um(rows, first(static_cast<int>(poses.size())),
                                positioning_criterion(robot, o.free, o.positioning, o.sigma, rows));
  };
  EXPECT_NEAR(pos.positioning_bound_um, bound_of(pos.poses), 1e-9 * pos.positioning_bound_um);
  EXPECT_LT(pos.positioning_bound_um, 0.95 * bound_of(worst.poses));
  EXPECT_EQ(parse_criterion("positioning"), Criterion::kPositioning);
  EXPECT_EQ(criterion_name(Criterion::kPositioning), "positioning");
}

TEST(PositioningDesign, FixedOffsetsAreRefused) {
  const Robot robot;
  FreeMask free = default_free_mask();
  free.reset(kDth1 + 1);
  try {
    rows_with_cyclic_error(robot, free, {robot.home});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("dth2 free"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace gpm::calib::excitation
