// Tests of calib/positioning_error.cpp: the model that is the robot positions
// without error; a model whose base is shifted by d positions every point off
// by exactly |d| (the mechanism is translation invariant), its map -d at
// every point; and parameter errors drawn from a covariance give a
// normalised error of 1 on average (the squared Mahalanobis distance of a
// 2-d Gaussian has mean 2), the map's points giving the RMS figures; the
// map's CSV reads back to it; a result's stated positioning is its own map.
#include "calib/positioning_error.hpp"

#include <array>
#include <cmath>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "models/rng.hpp"

namespace gpm::calib {
namespace {

TEST(PositioningError, TheRobotItselfPositionsWithoutError) {
  const Robot r;
  const PositioningError e = positioning_error(r, r, WorkspaceDisc{});
  EXPECT_GT(e.points, 150);  // 10 mm grid over an 80 mm disc: 197 points
  EXPECT_LT(e.max_um, 1e-6);
}

TEST(PositioningError, AShiftedBaseMissesEveryPointByTheShift) {
  const Robot actual;
  Robot model = actual;
  const Eigen::Vector2d d(0.003, -0.004);  // 5 um
  for (int i = 0; i < kNumChains; ++i) model.geometry[xa(i)] += d.x(), model.geometry[ya(i)] += d.y();
  const PositioningError e = positioning_error(actual, model, WorkspaceDisc{});
  EXPECT_NEAR(e.rms_um, 5.0, 1e-6);
  EXPECT_NEAR(e.max_um, 5.0, 1e-6);
  // The map: every point, each off by -d (the model's bases stand d from the actual ones).
  ASSERT_EQ(static_cast<int>(e.map.size()), e.points);
  for (const PositioningPoint& m : e.map) EXPECT_LT((m.error + d).norm(), 1e-9) << m.p.transpose();
}

// The CSV holds the map row by row and reads back to the same numbers, bit for bit.
TEST(PositioningError, TheCsvReadsBackToTheMap) {
  const Robot actual;
  Robot model = actual;
  model.geometry[kLa3] += 0.004, model.geometry[kDth2] -= 3e-5;
  Eigen::Matrix<double, kNumParams, kNumParams> C = Eigen::Matrix<double, kNumParams, kNumParams>::Zero();
  for (int k = 4; k < kNumParams; ++k) C(k, k) = is_offset(k) ? 1e-10 : 1e-6;
  const PositioningError e = positioning_error(actual, model, WorkspaceDisc{actual.home, 80.0, 40.0}, C);
  std::istringstream in(positioning_csv(e));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "x_mm,y_mm,error_x_um,error_y_um,error_um,sigma_um");
  size_t row = 0;
  while (std::getline(in, line)) {
    ASSERT_LT(row, e.map.size());
    std::array<double, 6> v{};
    std::istringstream fields(line);
    for (double& x : v) {
      std::string f;
      std::getline(fields, f, ',');
      x = std::stod(f);
    }
    const PositioningPoint& m = e.map[row++];
    EXPECT_EQ(v[0], m.p.x());
    EXPECT_EQ(v[1], m.p.y());
    EXPECT_EQ(v[2], m.error.x() * 1e3);
    EXPECT_EQ(v[3], m.error.y() * 1e3);
    EXPECT_EQ(v[4], (m.error * 1e3).norm());
    EXPECT_EQ(v[5], m.sigma_um);
    EXPECT_GT(v[5], 0.0);
  }
  EXPECT_EQ(row, e.map.size());
  EXPECT_EQ(static_cast<int>(row), e.points);
}

// A result's stated positioning is the map of the robot with its geometry
// judged against itself: no error, the 1-sigma its covariance gives; none
// without a covariance.
TEST(PositioningError, AResultsStatedPositioningIsItsOwnMap) {
  const Robot robot;
  Result r;
  r.geometry = robot.geometry;
  r.geometry[kLa3] += 0.004;
  EXPECT_FALSE(stated_positioning(robot, r).has_value());
  Eigen::Matrix<double, kNumParams, kNumParams> C = Eigen::Matrix<double, kNumParams, kNumParams>::Zero();
  for (int k = 4; k < kNumParams; ++k) C(k, k) = is_offset(k) ? 1e-10 : 1e-6;
  r.covariance = C;
  const auto stated = stated_positioning(robot, r);
  ASSERT_TRUE(stated.has_value());
  Robot calibrated = robot;
  calibrated.geometry = r.geometry;
  const PositioningError own = positioning_error(calibrated, calibrated, WorkspaceDisc{robot.home}, C);
  EXPECT_EQ(stated->stated_sigma_rms_um, own.stated_sigma_rms_um);
  EXPECT_GT(stated->stated_sigma_rms_um, 0.0);
  EXPECT_LT(stated->max_um, 1e-6);
  EXPECT_EQ(stated->carried_sigma_rms_um, 0.0);
}

TEST(PositioningError, ErrorsDrawnFromTheCovarianceAreCoveredByIt) {
  const Robot actual;
  Eigen::Matrix<double, kNumParams, kNumParams> C = Eigen::Matrix<double, kNumParams, kNumParams>::Zero();
  for (int k = 4; k < kNumParams; ++k) C(k, k) = is_offset(k) ? 1e-10 : 1e-6;  // 10 urad, 1 um; xa1..ya2 fixed
  const WorkspaceDisc coarse{actual.home, 80.0, 40.0};
  Rng rng(5);
  double mean_sq = 0.0, sigma = 0.0;
  const int draws = 200;
  for (int n = 0; n < draws; ++n) {
    Robot model = actual;
    for (int k = 4; k < kNumParams; ++k) model.geometry[k] += std::sqrt(C(k, k)) * rng.normal();
    const PositioningError e = positioning_error(actual, model, coarse, C);
    mean_sq += e.normalised_rms * e.normalised_rms / draws;
    sigma = e.stated_sigma_rms_um;
    double map_sigma2 = 0.0, map_error2 = 0.0;  // the map's points give the RMS figures
    for (const PositioningPoint& m : e.map) map_sigma2 += m.sigma_um * m.sigma_um, map_error2 += m.error.squaredNorm();
    EXPECT_NEAR(std::sqrt(map_sigma2 / e.points), e.stated_sigma_rms_um, 1e-9);
    EXPECT_NEAR(std::sqrt(map_error2 / e.points) * 1e3, e.rms_um, 1e-9);
  }
  EXPECT_NEAR(mean_sq, 1.0, 0.15);
  EXPECT_GT(sigma, 0.5);  // per-axis 1-sigma of a few um from 1 um / 10 urad parameters
  EXPECT_LT(sigma, 10.0);
}

// The carried part's 1-sigma adds in quadrature: the whole covariance
// carried gives the stated 1-sigma, a quarter of it half that, none 0; the
// covariance split in two parts gives two shares whose squares sum to it.
TEST(PositioningError, TheCarriedShareOfTheOneSigmaAddsInQuadrature) {
  const Robot actual;
  Eigen::Matrix<double, kNumParams, kNumParams> C = Eigen::Matrix<double, kNumParams, kNumParams>::Zero();
  for (int k = 4; k < kNumParams; ++k) C(k, k) = is_offset(k) ? 1e-10 : 1e-6;
  const WorkspaceDisc coarse{actual.home, 80.0, 40.0};
  const PositioningError all = positioning_error(actual, actual, coarse, C, C);
  EXPECT_NEAR(all.carried_sigma_rms_um, all.stated_sigma_rms_um, 1e-9);
  EXPECT_NEAR(positioning_error(actual, actual, coarse, C, 0.25 * C).carried_sigma_rms_um,
              0.5 * all.stated_sigma_rms_um, 1e-9);
  EXPECT_EQ(positioning_error(actual, actual, coarse, C).carried_sigma_rms_um, 0.0);
  Eigen::Matrix<double, kNumParams, kNumParams> lengths = C, offsets = C;
  for (int k = 0; k < kNumParams; ++k) (is_offset(k) ? lengths : offsets)(k, k) = 0.0;
  const double a = positioning_error(actual, actual, coarse, C, lengths).carried_sigma_rms_um;
  const double b = positioning_error(actual, actual, coarse, C, offsets).carried_sigma_rms_um;
  EXPECT_GT(a, 0.0);
  EXPECT_GT(b, 0.0);
  EXPECT_NEAR(a * a + b * b, all.stated_sigma_rms_um * all.stated_sigma_rms_um, 1e-9);
}

}  // namespace
}  // namespace gpm::calib
