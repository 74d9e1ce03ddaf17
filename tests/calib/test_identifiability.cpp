// Tests of calib/identifiability.cpp: the default 4-coordinate gauge has full
// rank 11, the paper's 3-coordinate gauge rank 11 of 12 with the null
// direction a scale-and-rotation about A1 (checked against the generators),
// all 15 free has 4 null directions, samples on a line are ill-conditioned
// (docs/EQUATIONS.md: ~1e10) and a disc of samples is well conditioned; the paper's
// section-4.4 setting (xa1, ya1, xa2 fixed, 50 workspace samples) is rank 11
// of 12 at the true values and its one-sentence diagnosis says so; the ML
// Jacobian equals central differences of the ML residual.
#include "calib/identifiability.hpp"

#include <gtest/gtest.h>

#include "calib/paper_values.hpp"
#include "calib/residuals.hpp"
#include "calib/synthetic.hpp"

namespace gpm::calib {
namespace {

std::vector<Eigen::Vector3d> disc(const Geometry& g, int n) {
  Robot r;
  r.geometry = g;
  return samples_at(r, disc_poses(r, n, r.home, 80.0, 3)).theta_m;
}

TEST(Identifiability, DefaultGaugeHasFullRank) {
  const Geometry g = table5_actual();
  const auto id = analyse_identifiability(disc(g, 50), Geometry::gpm2002_nominal(), default_free_mask());
  EXPECT_EQ(id.rank, 11);
  EXPECT_LT(id.condition_number, kPoorConditioning);
  EXPECT_TRUE(id.description.empty());
  std::printf("  condition number, 50 samples in a disc of 80 mm, 11 free: %.4g\n", id.condition_number);
}

TEST(Identifiability, ThreeCoordinateGaugeLosesScaleAndRotationAboutA1) {
  const Geometry g = section3_actual();
  const FreeMask free = ~parse_param_list("xa1,ya1,ya2", "test");
  const auto id = analyse_identifiability(disc(g, 31), g, free);
  EXPECT_EQ(id.rank, 11);
  std::printf("  3-coordinate gauge: smallest / largest singular value %.3g\n",
              id.singular_values[11] / id.singular_values[0]);
  ASSERT_EQ(id.null_vectors.cols(), 1);
  // The null vector is a combination of rotation and scale about A1 that keeps ya2.
  const auto G = gauge_generators(g);
  Eigen::Matrix<double, kNumParams, 1> v = Eigen::Matrix<double, kNumParams, 1>::Zero();
  for (size_t k = 0; k < id.free_index.size(); ++k) v[id.free_index[k]] = id.null_vectors(static_cast<Eigen::Index>(k), 0);
  const double rot = v[kDth1];                 // offsets turn by the rotation angle
  const double scale = v[kLa1] / g[kLa1];      // lengths grow by the scale
  EXPECT_GT(std::abs(rot), 1e-6);
  EXPECT_GT(std::abs(scale), 1e-6);
  EXPECT_LT((v - rot * G.col(2) - scale * G.col(3)).norm(), 1e-6 * v.norm());
  EXPECT_NE(id.description.find("scale and rotation about A1"), std::string::npos) << id.description;
  EXPECT_NE(id.advice.find("fix xa2"), std::string::npos) << id.advice;
}

TEST(Identifiability, AllFifteenFreeHaveFourNullDirections) {
  const Geometry g = table5_actual();
  FreeMask all;
  all.set();
  const auto id = analyse_identifiability(disc(g, 40), g, all);
  EXPECT_EQ(id.rank, 11);
  EXPECT_NE(id.description.find("translation"), std::string::npos) << id.description;
  EXPECT_NE(id.description.find("scale and rotation"), std::string::npos) << id.description;
}

std::vector<Eigen::Vector3d> workspace(int n) {
  Robot r;
  r.geometry = table5_actual();
  return workspace_samples(r, n, 42).theta_m;
}

TEST(Identifiability, PaperSection44SettingIsRankElevenOfTwelve) {
  const Identifiability id = analyse_identifiability(workspace(50), table5_actual(), paper_free_mask());
  EXPECT_EQ(id.free_count, 12);
  EXPECT_EQ(id.rank, 11);
  EXPECT_NE(id.diagnosis.find("rank 11 of 12"), std::string::npos) << id.diagnosis;
  EXPECT_NE(id.diagnosis.find("scale and rotation"), std::string::npos) << id.diagnosis;
}

TEST(Identifiability, FourFixedCoordinatesGiveFullRankAndSayIt) {
  const Identifiability id = analyse_identifiability(workspace(50), table5_actual(), default_free_mask());
  EXPECT_EQ(id.rank, 11);
  EXPECT_EQ(id.free_count, 11);
  EXPECT_LT(id.condition_number, kPoorConditioning);
  EXPECT_NE(id.diagnosis.find("rank 11 of 11: all free parameters identifiable"), std::string::npos)
      << id.diagnosis;
}

TEST(Identifiability, MlJacobianMatchesCentralDifferences) {
  const auto tm = workspace(20);
  Geometry g = table5_actual();
  g[kLb1] += 0.3;  // away from the perfect fit
  const Eigen::MatrixXd J = ml_jacobian(tm, g);
  auto residuals = [&](const Geometry& x) {
    Eigen::VectorXd r(static_cast<Eigen::Index>(tm.size()));
    for (size_t j = 0; j < tm.size(); ++j) {
      const MlResidual f(tm[j]);
      f(x.values.data(), &r[static_cast<Eigen::Index>(j)]);
    }
    return r;
  };
  for (int p = 0; p < kNumParams; ++p) {
    const double h = is_offset(p) ? 1e-6 : 1e-4;
    Geometry a = g, b = g;
    a[p] += h;
    b[p] -= h;
    const Eigen::VectorXd fd = (residuals(a) - residuals(b)) / (2 * h);
    EXPECT_LT((J.col(p) - fd).norm(), 1e-6 * fd.norm() + 1e-12) << param_name(p);
  }
}

TEST(Identifiability, SamplesOnALineAreIllConditioned) {
  Robot r;
  r.geometry = table5_actual();
  std::vector<Eigen::Vector2d> line;
  for (int j = 0; j < 30; ++j) line.emplace_back(160.0 + 4.0 * j, 250.0);
  const auto t = samples_at(r, line).theta_m;
  const auto id = analyse_identifiability(t, Geometry::gpm2002_nominal(), default_free_mask());
  EXPECT_EQ(id.rank, 11) << "practically, not exactly, unidentifiable";
  EXPECT_GT(id.condition_number, kPoorConditioning);
  std::printf("  condition number, 30 samples on a line: %.4g (rank %d)\n", id.condition_number, id.rank);
}

}  // namespace
}  // namespace gpm::calib
