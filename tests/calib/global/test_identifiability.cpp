// Rank of the closure Jacobian: 11 of 12 in the paper's setting (similarity
// family, ERRATA), 11 of 11 with xa1, ya1, xa2, ya2 fixed.
#include "calib/global/identifiability.hpp"

#include <gtest/gtest.h>

#include "calib/global/closure_kernel.hpp"
#include "calib/global/synthetic.hpp"
#include "models/kinematics.hpp"

namespace gpm::calib::global {
namespace {

std::vector<Eigen::Vector3d> readings() {
  Robot r;
  r.geometry = table5_actual();
  return workspace_samples(r, 50, 42).theta_m;
}

// g_j from the models library's forward kinematics (its `power`).
Eigen::VectorXd residuals(const std::vector<Eigen::Vector3d>& tm, const Geometry& g) {
  Eigen::VectorXd r(static_cast<long>(tm.size()));
  for (size_t j = 0; j < tm.size(); ++j) r[static_cast<long>(j)] = forward_kinematics(g, active_from_readings(g, tm[j]))->power;
  return r;
}

TEST(Identifiability, AnalyticJacobianMatchesCentralDifferences) {
  const auto tm = readings();
  Geometry g = table5_actual();
  g[kLb1] += 0.3;  // away from the perfect fit
  FreeMask all;
  all.set();
  const Eigen::MatrixXd J = closure_jacobian(tm, g, all);
  for (int p = 0; p < kNumParams; ++p) {
    const double h = is_offset(p) ? 1e-6 : 1e-4;
    Geometry a = g, b = g;
    a[p] += h;
    b[p] -= h;
    const Eigen::VectorXd fd = (residuals(tm, a) - residuals(tm, b)) / (2 * h);
    EXPECT_LT((J.col(p) - fd).norm(), 1e-5 * fd.norm() + 1e-8) << param_name(p);
  }
}

TEST(Identifiability, PaperSettingIsRankElevenOfTwelveAlongTheSimilarityFamily) {
  const Identifiability id = closure_identifiability(readings(), table5_actual(), paper_free_mask());
  EXPECT_EQ(id.free_count, 12);
  EXPECT_EQ(id.rank, 11);
  EXPECT_GT(id.similarity_alignment, 0.999);
  EXPECT_NE(id.diagnosis.find("rank 11 of 12"), std::string::npos);
  EXPECT_NE(id.diagnosis.find("scale and rotation"), std::string::npos);
}

TEST(Identifiability, FourFixedCoordinatesGiveFullRank) {
  const Identifiability id = closure_identifiability(readings(), table5_actual(), default_free_mask());
  EXPECT_EQ(id.rank, 11);
  EXPECT_EQ(id.free_count, 11);
  EXPECT_LT(id.condition_number, 1e6);
  EXPECT_TRUE(std::isnan(id.similarity_alignment));
  EXPECT_NE(id.diagnosis.find("all free parameters identifiable"), std::string::npos);
}

TEST(Identifiability, MovingAlongTheFamilyKeepsThePerfectFit) {
  // A finite step along the similarity direction: closure residuals stay tiny
  // to first order (the family is exact; its direction here is linearised).
  const auto tm = readings();
  const Geometry g = table5_actual();
  const auto v = similarity_direction(g, paper_free_mask());
  EXPECT_EQ(v[kXa1], 0.0);
  EXPECT_EQ(v[kXa2], 0.0);
  EXPECT_NEAR(v.norm(), 1.0, 1e-12);
  Geometry moved = g;
  for (int p = 0; p < kNumParams; ++p) moved[p] += 1e-4 * v[p];
  Geometry other = g;
  other[kLb1] += 1e-4;  // a step of the same size off the family
  EXPECT_LT(residuals(tm, moved).norm(), 1e-3 * residuals(tm, other).norm());
}

}  // namespace
}  // namespace gpm::calib::global
