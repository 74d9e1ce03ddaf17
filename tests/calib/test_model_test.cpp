// Tests of calib/model_test.cpp: the chi-square statistic follows its
// distribution on data generated under the model (mean dof, p-values spread
// over (0, 1)), and a smooth unmodelled bias, a small inflation of every
// residual or a few outliers make it fail with the matching diagnosis; the
// share a carried error explains, three ways.
#include "calib/model_test.hpp"

#include <cmath>
#include <numbers>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "calib/chi_square.hpp"
#include "calib/lm.hpp"
#include "calib/paper_values.hpp"
#include "calib/synthetic.hpp"
#include "models/errors.hpp"
#include "models/rng.hpp"

namespace gpm::calib {
namespace {

constexpr double kSigma = 1e-4;

Robot actual_robot() {
  Robot r;
  r.geometry = table5_actual();
  return r;
}

// Calibrates from readings (start nominal) and returns the fitted geometry.
Geometry fit(const std::vector<Eigen::Vector3d>& theta_m) {
  Problem p;
  p.theta_m = theta_m;
  p.start = Robot{}.geometry;
  for (int k : {kXa1, kYa1, kXa2, kYa2}) p.start.values[k] = table5_actual().values[k];
  p.free = default_free_mask();
  LmOptions o;
  o.compute_covariance = false;
  return calibrate_lm(p, o).geometry;
}

// Readings of 80 poses over a 90 mm disc with reading 2 off by amplitude x
// sin(40 theta_1): an unmodelled bias spread over the samples.
Samples biased_samples(double amplitude) {
  const Robot a = actual_robot();
  Samples smp = samples_at(a, disc_poses(a, 80, a.home, 90.0, 7), kSigma, 8);
  for (auto& t : smp.theta_m) t[1] += amplitude * std::sin(40.0 * t[0]);
  return smp;
}

TEST(ModelTest, UnderTheModelChiSquareHasItsMeanAndPValuesSpread) {
  const Robot a = actual_robot();
  const int n = 60, seeds = 20;
  int rejected = 0;
  double mean_ratio = 0.0;
  for (int s = 0; s < seeds; ++s) {
    const auto poses = disc_poses(a, n, a.home, 90.0, 100 + s);
    const Samples smp = samples_at(a, poses, kSigma, 200 + s);
    const ModelTest t = model_test(fit(smp.theta_m), default_free_mask(), smp.theta_m, kSigma, 0.05);
    EXPECT_EQ(t.dof, n - 11);
    EXPECT_GT(t.p_value, 0.0);
    EXPECT_LE(t.p_value, 1.0);
    rejected += !t.passed;
    mean_ratio += t.chi2 / t.dof / seeds;
  }
  // E[chi2 / dof] = 1 with sd sqrt(2 / dof) per trial: over 20 trials, 4 sd = 0.18.
  EXPECT_NEAR(mean_ratio, 1.0, 0.18);
  // At alpha = 0.05, 1 rejection expected in 20; P(more than 5) < 0.3 %.
  EXPECT_LE(rejected, 5);
}

TEST(ModelTest, SpreadUnmodelledBiasFailsAsAnUnmodelledEffect) {
  const Robot a = actual_robot();
  const auto poses = disc_poses(a, 80, a.home, 90.0, 7);
  Samples smp = samples_at(a, poses, kSigma, 8);
  // A pose-dependent error of joint 2 that no parameter change can absorb
  // (several periods across the workspace), 6 sigma at its peak. (A smooth
  // one, such as 6 sigma cos(theta_1), is absorbed by the 11 parameters and
  // biases them without raising chi2: the test cannot see it, by design.)
  for (auto& t : smp.theta_m) t[1] += 6.0 * kSigma * std::sin(40.0 * t[0]);
  const ModelTest t = model_test(fit(smp.theta_m), default_free_mask(), smp.theta_m, kSigma);
  EXPECT_FALSE(t.passed);
  EXPECT_GT(t.rms_ratio, 1.5);
  EXPECT_NE(t.diagnosis.find("unmodelled effect"), std::string::npos) << t.diagnosis;
}

// An effect that inflates every residual by a few per cent fails the test
// on enough samples and is an unmodelled effect, not outliers: under the
// model the largest 1 % of the squared residuals alone average 8.45, which
// outweighs an excess of 0.12 dof (the diagnosis once counted them as
// outliers; the main job's realistic twin showed it).
TEST(ModelTest, SmallSpreadExcessOnManySamplesIsNotOutliers) {
  const Robot a = actual_robot();
  const auto poses = disc_poses(a, 3000, a.home, 90.0, 11);
  const Samples smp = samples_at(a, poses, 1.06 * kSigma, 12);
  const ModelTest t = model_test(fit(smp.theta_m), default_free_mask(), smp.theta_m, kSigma);
  // chi2 / dof = 1.12 +- 0.026: failing at alpha 0.01 with near certainty.
  EXPECT_FALSE(t.passed) << t.chi2 / t.dof;
  EXPECT_NEAR(t.rms_ratio, 1.06, 0.03);
  EXPECT_NE(t.diagnosis.find("unmodelled effect"), std::string::npos) << t.diagnosis;
}

// The same many samples, noise as stated, and a handful of gross errors:
// outliers, though they are fewer than 1 % of the samples.
TEST(ModelTest, FewGrossErrorsAmongManySamplesAreOutliers) {
  const Robot a = actual_robot();
  const auto poses = disc_poses(a, 3000, a.home, 90.0, 13);
  Samples smp = samples_at(a, poses, kSigma, 14);
  for (const int j : {100, 900, 2500}) smp.theta_m[j][j % 3] += 40.0 * kSigma;
  const ModelTest t = model_test(fit(smp.theta_m), default_free_mask(), smp.theta_m, kSigma);
  EXPECT_FALSE(t.passed) << t.chi2 / t.dof;
  EXPECT_NE(t.diagnosis.find("outlier"), std::string::npos) << t.diagnosis;
  EXPECT_NE(t.diagnosis.find(": 3 residual(s)"), std::string::npos) << t.diagnosis;
}

TEST(ModelTest, FewLargeErrorsFailAsOutliersAndAreListedFirst) {
  const Robot a = actual_robot();
  const auto poses = disc_poses(a, 80, a.home, 90.0, 9);
  Samples smp = samples_at(a, poses, kSigma, 10);
  smp.theta_m[17][2] += 300.0 * kSigma;
  const ModelTest t = model_test(fit(smp.theta_m), default_free_mask(), smp.theta_m, kSigma);
  EXPECT_FALSE(t.passed);
  ASSERT_FALSE(t.worst_samples.empty());
  EXPECT_EQ(t.worst_samples.front(), 17);
  EXPECT_NE(t.diagnosis.find("outlier"), std::string::npos) << t.diagnosis;
}

// Three formulations of the marginal test's share agree: the closed form,
// the ridge fit's chi-square drop (an augmented least-squares problem solved
// by QR) and the Woodbury identity on the dense residual covariance
// sigma2 I + prior^2 G G'; a vanishing prior explains nothing, an unbounded
// one the whole projection of r on G.
TEST(ModelTest, CarriedChiSquareIsTheRidgeFitsDropAndTheMarginalFormsOne) {
  const int n = 60, q = 4;
  const double sigma2 = 4e-12, prior = 3e-6;
  const Eigen::MatrixXd G = Eigen::MatrixXd::Random(n, q);
  const Eigen::VectorXd r = 2e-6 * Eigen::VectorXd::Random(n) + G * Eigen::Vector4d(1e-6, -2e-6, 5e-7, 3e-6);
  const double chi2 = r.squaredNorm() / sigma2;
  const double share = carried_chi2(G, r, prior, sigma2);
  Eigen::MatrixXd A(n + q, q);
  A << G / std::sqrt(sigma2), Eigen::MatrixXd::Identity(q, q) / prior;
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n + q);
  b.head(n) = r / std::sqrt(sigma2);
  const Eigen::VectorXd c = A.colPivHouseholderQr().solve(b);
  EXPECT_NEAR(share, chi2 - (A * c - b).squaredNorm(), 1e-9 * chi2);
  Eigen::MatrixXd V = prior * prior * G * G.transpose();
  V.diagonal().array() += sigma2;
  EXPECT_NEAR(chi2 - share, r.dot(V.ldlt().solve(r)), 1e-9 * chi2);
  EXPECT_GT(share, 0.0);
  EXPECT_LT(carried_chi2(G, r, 1e-12, sigma2), 1e-6 * share);
  const Eigen::VectorXd Pr = G * G.colPivHouseholderQr().solve(r);
  EXPECT_NEAR(carried_chi2(G, r, 1.0, sigma2), Pr.squaredNorm() / sigma2, 1e-6 * chi2);
  EXPECT_EQ(carried_chi2(Eigen::MatrixXd(n, 0), r, prior, sigma2), 0.0);
  EXPECT_THROW(carried_chi2(G, r, 0.0, sigma2), InputError);
}

// The test weighs the chi-square less what a carried error explains: the
// misfit of SpreadUnmodelledBias fails as it stands and passes when a
// carried error is said to explain all of its excess; never below zero.
TEST(ModelTest, WeighsTheChiSquareLessTheCarriedShare) {
  const Samples smp = biased_samples(6.0 * kSigma);
  const Geometry g = fit(smp.theta_m);
  const ModelTest plain = model_test(g, default_free_mask(), smp.theta_m, kSigma);
  ASSERT_FALSE(plain.passed);
  const double excess = plain.chi2 - plain.dof;
  const ModelTest carried = model_test(g, default_free_mask(), smp.theta_m, kSigma, 0.01, excess);
  EXPECT_NEAR(carried.chi2, plain.dof, 1e-9 * plain.chi2);
  EXPECT_NEAR(carried.carried_chi2, excess, 1e-9 * plain.chi2);
  EXPECT_TRUE(carried.passed);
  EXPECT_GT(carried.p_value, plain.p_value);
  const ModelTest all = model_test(g, default_free_mask(), smp.theta_m, kSigma, 0.01, 10.0 * plain.chi2);
  EXPECT_NEAR(all.chi2, 0.0, 1e-9 * plain.chi2);
}

TEST(ModelTest, SampleDoubtSumsWhatEachWeightAdds) {
  Eigen::VectorXd w(3);
  w << 1.0, 0.5, 1.0 / std::sqrt(2.0);  // lambda = 1, 4, 2
  const SampleDoubt d = sample_doubt(w);
  EXPECT_NEAR(d.mean, 0.0 + 3.0 + 1.0, 1e-12);
  EXPECT_NEAR(d.spread, 0.0 + 15.0 + 3.0, 1e-12);
  const SampleDoubt none = sample_doubt(Eigen::VectorXd());
  EXPECT_EQ(none.mean, 0.0);
  EXPECT_EQ(none.spread, 0.0);
}

TEST(ModelTest, WithoutDoubtTheSurvivalIsTheChiSquares) {
  for (double x : {80.0, 100.0, 130.0}) EXPECT_EQ(doubted_chi2_survival(100.0, {}, x), chi2_survival(100.0, x));
}

// Residuals whose variance is lambda_j sigma^2, a tenth of them at lambda 4
// (a joint that may rest), summed by sigma alone: drawn 4000 times, the
// doubted p-value is spread as a p-value is (its 1 % and 50 % quantiles
// where they belong), where the chi-square's own rejects most draws.
TEST(ModelTest, TheDoubtedSurvivalHoldsItsLevelOnResidualsOfThatVariance) {
  const int n = 2000, trials = 4000;
  Eigen::VectorXd w = Eigen::VectorXd::Ones(n);
  for (int j = 0; j < n; j += 10) w[j] = 0.5;
  const SampleDoubt d = sample_doubt(w);
  Rng rng(42);
  int below_1 = 0, below_50 = 0, plain_below_1 = 0;
  for (int t = 0; t < trials; ++t) {
    double chi2 = 0.0;
    for (int j = 0; j < n; ++j) chi2 += std::pow(rng.normal() / w[j], 2);
    const double p = doubted_chi2_survival(n, d, chi2);
    below_1 += p < 0.01, below_50 += p < 0.5;
    plain_below_1 += chi2_survival(n, chi2) < 0.01;
  }
  // Binomial sd: 1 %: 6.3 of 4000 (40 expected), 50 %: 32 (2000 expected).
  EXPECT_NEAR(below_1, 40, 25);
  EXPECT_NEAR(below_50, 2000, 130);
  EXPECT_GT(plain_below_1, trials / 2);
}

TEST(ModelTest, ExpectsTheDoubtsShareAndRecordsIt) {
  const Samples smp = biased_samples(3.0 * kSigma);
  const Geometry g = fit(smp.theta_m);
  const ModelTest plain = model_test(g, default_free_mask(), smp.theta_m, kSigma);
  ASSERT_FALSE(plain.passed);
  const double excess = plain.chi2 - plain.dof;  // as if from samples of lambda 2: E = 3 D
  const ModelTest doubted = model_test(g, default_free_mask(), smp.theta_m, kSigma, 0.01, 0.0, {excess, 3.0 * excess});
  EXPECT_EQ(doubted.chi2, plain.chi2);  // summed unweighted as before
  EXPECT_EQ(doubted.doubt_chi2, excess);
  EXPECT_TRUE(doubted.passed);
  EXPECT_GT(doubted.p_value, 0.3);
  EXPECT_EQ(plain.doubt_chi2, 0.0);
  // A doubt of a tenth of the excess does not cover it.
  EXPECT_FALSE(model_test(g, default_free_mask(), smp.theta_m, kSigma, 0.01, 0.0, {0.1 * excess, 0.3 * excess}).passed);
}

TEST(ModelTest, RefusesMeaninglessSettings) {
  const Robot a = actual_robot();
  const Samples smp = samples_at(a, disc_poses(a, 20, a.home, 90.0, 1));
  EXPECT_THROW(model_test(a.geometry, default_free_mask(), smp.theta_m, 0.0), InputError);
  EXPECT_THROW(model_test(a.geometry, default_free_mask(), smp.theta_m, kSigma, 1.5), InputError);
  const std::vector<Eigen::Vector3d> few(smp.theta_m.begin(), smp.theta_m.begin() + 11);
  EXPECT_THROW(model_test(a.geometry, default_free_mask(), few, kSigma), InputError);
}

}  // namespace
}  // namespace gpm::calib
