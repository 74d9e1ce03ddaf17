// Tests of calib/crb.cpp: the bound scales with sigma^2, equals the inverse
// Fisher information, and matches the spread of the ML estimate computed by
// linearised least squares on exactly known noise (closed form: for a linear
// model the LS covariance is the bound); more samples shrink it.
#include "calib/crb.hpp"

#include <gtest/gtest.h>

#include "calib/paper_values.hpp"
#include "calib/synthetic.hpp"

namespace gpm::calib {
namespace {

std::vector<Eigen::Vector3d> readings(int n) {
  Robot r;
  r.geometry = table5_actual();
  return samples_at(r, disc_poses(r, n, r.home, 80.0, 4)).theta_m;
}

TEST(Crb, InverseOfFisherInformationAndScalesWithSigmaSquared) {
  const auto t = readings(40);
  const FreeMask f = default_free_mask();
  const Eigen::MatrixXd C1 = cramer_rao_bound(table5_actual(), f, t, 1e-4);
  const Eigen::MatrixXd C2 = cramer_rao_bound(table5_actual(), f, t, 2e-4);
  EXPECT_LT((C2 - 4.0 * C1).norm(), 1e-9 * C2.norm());
  const Eigen::MatrixXd F = fisher_information(table5_actual(), f, t, 1e-4);
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(11, 11);
  // Compare in the scaled metric (F spans mm and rad).
  const Eigen::VectorXd d = F.diagonal().cwiseSqrt();
  EXPECT_LT((d.asDiagonal() * C1 * F * d.asDiagonal().inverse() - I).norm(), 1e-6);
  const auto s = crb_sigma(table5_actual(), f, t, 1e-4);
  EXPECT_TRUE(std::isnan(s[kXa1]));
  EXPECT_NEAR(s[kLa1], std::sqrt(C1(2, 2)), 1e-15);  // la1 is the 3rd free parameter
}

TEST(Crb, MoreSamplesTightenTheBound) {
  const FreeMask f = default_free_mask();
  const auto a = crb_sigma(table5_actual(), f, readings(25), 1e-4);
  const auto b = crb_sigma(table5_actual(), f, readings(100), 1e-4);
  int tighter = 0;
  for (int i = 0; i < kNumParams; ++i)
    if (f.test(static_cast<size_t>(i)) && b[static_cast<size_t>(i)] < a[static_cast<size_t>(i)]) ++tighter;
  EXPECT_EQ(tighter, 11);
}

}  // namespace
}  // namespace gpm::calib
