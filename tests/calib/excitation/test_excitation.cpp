// Tests of calib/excitation/excitation.hpp: the optimised set is never worse
// than its greedy start, every pose is reachable with the margins, D-optimal
// beats a random disc, the exchange steps do what their formulas promise, and
// bad options are one-line input errors.
#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/LU>
#include <random>
#include <set>

#include "calib/excitation/excitation.hpp"
#include "calib/synthetic.hpp"
#include "models/errors.hpp"
#include "models/kinematics.hpp"

namespace gpm::calib::excitation {
namespace {

DesignOptions small_options(Criterion c) {
  DesignOptions o;
  o.count = 20;
  o.criterion = c;
  o.grid_step_mm = 10.0;
  return o;
}

void expect_valid_poses(const Robot& robot, const Design& d, int count) {
  ASSERT_EQ(static_cast<int>(d.poses.size()), count);
  std::set<std::pair<double, double>> distinct;
  for (const auto& p : d.poses) {
    const Reach r = check_reach(robot, p);
    EXPECT_TRUE(r.ok) << p.transpose() << ": " << r.reason;
    distinct.insert({p.x(), p.y()});
  }
  EXPECT_EQ(static_cast<int>(distinct.size()), count);
}

TEST(Excitation, DOptimalNeverWorseThanStartAndReachable) {
  const Robot nominal;
  const Design d = design_poses(nominal, small_options(Criterion::kDOptimal));
  expect_valid_poses(nominal, d, 20);
  EXPECT_GE(d.bounds.log_det, d.start_bounds.log_det);
  // recomputed independently from the poses
  EXPECT_NEAR(pose_bounds(nominal, default_free_mask(), d.poses, 1e-4).log_det, d.bounds.log_det, 1e-6);
}

TEST(Excitation, WorstNeverWorseThanStartAndReachable) {
  const Robot nominal;
  const Design d = design_poses(nominal, small_options(Criterion::kWorst));
  expect_valid_poses(nominal, d, 20);
  EXPECT_LE(d.bounds.worst_mm, d.start_bounds.worst_mm);
  EXPECT_GT(d.exchanges, 0);
  EXPECT_NEAR(pose_bounds(nominal, default_free_mask(), d.poses, 1e-4).worst_mm, d.bounds.worst_mm,
              1e-9 * d.bounds.worst_mm);
}

TEST(Excitation, ProgressCountsEveryStageOnceAndLeavesTheDesignUnchanged) {
  // Greedy start, then the D exchange (D criterion: 2 stages) or the D
  // exchange and the four variance exchanges q = 1, 4, 16, inf (worst: 6).
  const Robot nominal;
  for (const auto& [c, stages] : {std::pair{Criterion::kDOptimal, 2}, std::pair{Criterion::kWorst, 6}}) {
    DesignOptions o = small_options(c);
    std::vector<int> seen;
    o.progress = [&](int done, int total) {
      EXPECT_EQ(total, stages);
      seen.push_back(done);
    };
    const Design with = design_poses(nominal, o);
    o.progress = nullptr;
    const Design without = design_poses(nominal, o);
    std::vector<int> expected(static_cast<size_t>(stages));
    for (int k = 0; k < stages; ++k) expected[static_cast<size_t>(k)] = k + 1;
    EXPECT_EQ(seen, expected) << criterion_name(c);
    EXPECT_EQ(with.poses, without.poses) << criterion_name(c);
  }
}

TEST(Excitation, DOptimalBeatsRandomDiscs) {
  const Robot nominal;
  DesignOptions o = small_options(Criterion::kDOptimal);
  o.count = 50;
  const Design d = design_poses(nominal, o);
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    for (double radius : {80.0, 150.0}) {
      const Bounds disc = pose_bounds(nominal, o.free, disc_poses(nominal, 50, nominal.home, radius, seed), o.sigma);
      EXPECT_GT(d.bounds.log_det, disc.log_det) << "radius " << radius << " seed " << seed;
      EXPECT_LT(d.bounds.worst_mm, disc.worst_mm) << "radius " << radius << " seed " << seed;
    }
  }
}

TEST(Excitation, DesignDoesNotDependOnSigma) {
  const Robot nominal;
  DesignOptions o = small_options(Criterion::kWorst);
  const Design a = design_poses(nominal, o);
  o.sigma = 1e-3;
  const Design b = design_poses(nominal, o);
  ASSERT_EQ(a.poses.size(), b.poses.size());
  for (size_t k = 0; k < a.poses.size(); ++k) EXPECT_EQ(a.poses[k], b.poses[k]);
  EXPECT_NEAR(b.bounds.worst_mm, 10.0 * a.bounds.worst_mm, 1e-6 * b.bounds.worst_mm);
}

// Random rows in 3-D: the exchanges against brute force over all subsets.
Eigen::MatrixXd random_rows(int n, int p, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> z;
  Eigen::MatrixXd r(n, p);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < p; ++k) r(i, k) = z(rng) * (k + 1);
  return r;
}

double logdet_of(const Eigen::MatrixXd& rows, const std::vector<int>& idx) {
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(rows.cols(), rows.cols());
  for (int j : idx) M += rows.row(j).transpose() * rows.row(j);
  return std::log(M.determinant());
}

double max_var_of(const Eigen::MatrixXd& rows, const std::vector<int>& idx) {
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(rows.cols(), rows.cols());
  for (int j : idx) M += rows.row(j).transpose() * rows.row(j);
  return M.inverse().diagonal().maxCoeff();
}

TEST(Excitation, ExchangesImproveAndReachLocalOptimaOfBruteForce) {
  const int n = 12, p = 3, count = 4;
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const Eigen::MatrixXd rows = random_rows(n, p, seed);
    std::vector<int> chosen = greedy_d_optimal(rows, count);
    ASSERT_EQ(chosen.size(), 4u);
    const double start = logdet_of(rows, chosen);
    exchange_d_optimal(rows, chosen, 100);
    const double after = logdet_of(rows, chosen);
    EXPECT_GE(after, start - 1e-12);
    // No single swap improves it any more (checked by brute force).
    for (size_t a = 0; a < chosen.size(); ++a)
      for (int j = 0; j < n; ++j) {
        if (std::find(chosen.begin(), chosen.end(), j) != chosen.end()) continue;
        auto other = chosen;
        other[a] = j;
        EXPECT_LE(logdet_of(rows, other), after + 1e-9);
      }
    // Same for the worst variance (q = 0).
    const double v0 = max_var_of(rows, chosen);
    exchange_variances(rows, chosen, 0, 100);
    const double v1 = max_var_of(rows, chosen);
    EXPECT_LE(v1, v0 * (1 + 1e-12));
    for (size_t a = 0; a < chosen.size(); ++a)
      for (int j = 0; j < n; ++j) {
        if (std::find(chosen.begin(), chosen.end(), j) != chosen.end()) continue;
        auto other = chosen;
        other[a] = j;
        EXPECT_GE(max_var_of(rows, other), v1 * (1 - 1e-9));
      }
  }
}

TEST(Excitation, BadOptionsAreInputErrors) {
  const Robot nominal;
  DesignOptions o = small_options(Criterion::kWorst);
  o.count = 10;  // fewer than 11 free parameters
  EXPECT_THROW(design_poses(nominal, o), InputError);
  o = small_options(Criterion::kWorst);
  o.sigma = 0.0;
  EXPECT_THROW(design_poses(nominal, o), InputError);
  o = small_options(Criterion::kWorst);
  o.free.set();  // the similarity gauge is not fixed
  EXPECT_THROW(design_poses(nominal, o), InputError);
  o = small_options(Criterion::kWorst);
  o.count = 100000;
  EXPECT_THROW(design_poses(nominal, o), InputError);
  EXPECT_EQ(parse_criterion("d"), Criterion::kDOptimal);
  EXPECT_EQ(parse_criterion("worst"), Criterion::kWorst);
  EXPECT_FALSE(parse_criterion("a").has_value());
}

}  // namespace
}  // namespace gpm::calib::excitation
