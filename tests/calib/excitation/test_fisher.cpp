// Tests of calib/excitation/fisher.hpp: the Fisher information of poses agrees
// with calib/crb.hpp, has the similarity gauge as its null space, and the
// scaled bounds follow their definition.
#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/LU>

#include "calib/crb.hpp"
#include "calib/excitation/fisher.hpp"
#include "calib/identifiability.hpp"
#include "calib/synthetic.hpp"
#include "models/errors.hpp"

namespace gpm::calib::excitation {
namespace {

std::vector<Eigen::Vector2d> some_poses(int n = 30) {
  return disc_poses(Robot{}, n, {216.5, 250.0}, 120.0, 7);
}

TEST(Fisher, AgreesWithCramerRaoBoundOfCalib) {
  const Robot nominal;
  const FreeMask free = default_free_mask();
  const auto poses = some_poses();
  const double sigma = 1e-4;
  const Samples s = samples_at(nominal, poses);  // noiseless readings
  const Eigen::MatrixXd crb = cramer_rao_bound(nominal.geometry, free, s.theta_m, sigma);
  const Eigen::MatrixXd F = fisher_information(information_rows(nominal, free, poses), sigma);
  const Eigen::MatrixXd ours = F.inverse();
  ASSERT_EQ(ours.rows(), crb.rows());
  EXPECT_LT((ours - crb).norm(), 1e-6 * crb.norm());
  const auto sig = crb_sigma(nominal.geometry, free, s.theta_m, sigma);
  const Bounds b = pose_bounds(nominal, free, poses, sigma);
  for (size_t k = 0; k < b.free_index.size(); ++k)
    EXPECT_NEAR(b.sigma[static_cast<Eigen::Index>(k)], sig[static_cast<size_t>(b.free_index[k])],
                1e-6 * sig[static_cast<size_t>(b.free_index[k])]);
}

TEST(Fisher, SimilarityGaugeIsItsNullSpaceWhenAllFree) {
  // docs/EQUATIONS.md: encoder angles cannot see translation, rotation and scale.
  const Robot nominal;
  FreeMask all;
  all.set();
  const Eigen::MatrixXd rows = information_rows(nominal, all, some_poses());
  const Eigen::MatrixXd G = gauge_generators(nominal.geometry);
  EXPECT_LT((rows * G).norm(), 1e-9 * rows.norm() * G.norm());
  const Bounds b = bounds_from_rows(rows, nominal.geometry, all, 1e-4);
  EXPECT_TRUE(std::isinf(b.worst_mm));
  EXPECT_TRUE(std::isinf(b.log_det) && b.log_det < 0);
}

TEST(Fisher, ScaledBoundsFollowTheirDefinition) {
  const Robot nominal;
  const FreeMask free = default_free_mask();
  const auto poses = some_poses();
  const Bounds b1 = pose_bounds(nominal, free, poses, 1e-4);
  const Bounds b2 = pose_bounds(nominal, free, poses, 2e-4);
  ASSERT_EQ(b1.free_index.size(), 11u);
  double worst = 0.0, sum = 0.0;
  for (size_t k = 0; k < b1.free_index.size(); ++k) {
    const auto kk = static_cast<Eigen::Index>(k);
    const int i = b1.free_index[k];
    const double scale = is_offset(i) ? nominal.geometry.la_(i - kDth1) : 1.0;
    EXPECT_NEAR(b1.scaled[kk], b1.sigma[kk] * scale, 1e-12 * b1.scaled[kk]);
    EXPECT_NEAR(b2.sigma[kk], 2.0 * b1.sigma[kk], 1e-9 * b1.sigma[kk]);  // linear in the noise
    worst = std::max(worst, b1.scaled[kk]);
    sum += b1.scaled[kk];
  }
  EXPECT_DOUBLE_EQ(b1.worst_mm, worst);
  EXPECT_NEAR(b1.mean_mm, sum / 11.0, 1e-12 * sum);
  // log det F grows by -2 p log 2 when sigma doubles.
  EXPECT_NEAR(b2.log_det, b1.log_det - 22.0 * std::log(2.0), 1e-6);
}

TEST(Fisher, UnreachablePoseIsAnInputError) {
  EXPECT_THROW(information_rows(Robot{}, default_free_mask(), {{216.5, 900.0}}), InputError);
  EXPECT_THROW(fisher_information(Eigen::MatrixXd::Ones(3, 2), 0.0), InputError);
}

}  // namespace
}  // namespace gpm::calib::excitation
