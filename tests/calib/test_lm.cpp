// Tests of calib/lm.cpp: the paper's stepwise experiments (section 3.3,
// Tables 2-4) on generated noiseless data with the section-3 actual values
// (docs/EQUATIONS.md: la3 = 244.5) from the paper's initial estimates; every error
// function must recover the actual values to 1e-6 mm / rad. Also the
// 12-parameter gauge refused as rank-deficient, the minimum-norm solve, bad
// input, the 1-sigma against the Cramer-Rao bound, the analytic Jacobians
// giving the autodiff reference's estimate and 1-sigma on noisy data, and
// noisy fits ending at the optimum (the Gauss-Newton step there is nil),
// and the samples' weights (a zero weight, a uniform one).
#include "calib/lm.hpp"

#include <cmath>
#include <memory>

#include <Eigen/Dense>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "calib/crb.hpp"
#include "calib/parameterization.hpp"
#include "calib/residuals.hpp"
#include "calib/paper_values.hpp"
#include "calib/synthetic.hpp"
#include "models/errors.hpp"

namespace gpm::calib {
namespace {

Robot robot_of(const Geometry& g) {
  Robot r;
  r.geometry = g;
  return r;
}

Samples paper_samples(const Geometry& actual, int n, std::uint64_t seed) {
  const Robot r = robot_of(actual);
  return samples_at(r, disc_poses(r, n, r.home, 100.0, seed));
}

// Runs one case and checks every free parameter against the actual value.
Result expect_recovers(const Geometry& actual, const Geometry& start, const FreeMask& free, int n,
                       Cost cost, double tol = 1e-6) {
  const Samples s = paper_samples(actual, n, 42 + static_cast<std::uint64_t>(n));
  Problem pb{s.theta_m, start, free};
  LmOptions opt;
  opt.cost = cost;
  pb.true_xy = s.xy;
  const Result r = calibrate_lm(pb, opt);
  EXPECT_TRUE(r.converged) << cost_name(cost);
  for (int i = 0; i < kNumParams; ++i) {
    if (free.test(static_cast<size_t>(i))) {
      EXPECT_NEAR(r.geometry[i], actual[i], tol) << cost_name(cost) << " " << param_name(i);
    } else {
      EXPECT_EQ(r.geometry[i], start[i]) << "fixed " << param_name(i) << " moved";
    }
  }
  EXPECT_TRUE(r.kmrmse_mm.has_value());
  EXPECT_LT(*r.kmrmse_mm, 1e-6);
  EXPECT_EQ(r.rank, static_cast<int>(free.count()));
  ::testing::Test::RecordProperty(fmt::format("kmrmse_{}_{}", cost_name(cost), free.count()), fmt::format("{:.3g}", *r.kmrmse_mm));
  std::printf("  %s, %zu free, %d samples: J = %.3g, kmrmse = %.3g mm, %ld iterations\n",
              std::string(cost_name(cost)).c_str(), free.count(), n, r.final_cost, *r.kmrmse_mm, r.iterations);
  return r;
}

Geometry with_offsets(Geometry g, double d1, double d2, double d3) {
  g[kDth1] = d1;
  g[kDth2] = d2;
  g[kDth3] = d3;
  return g;
}

FreeMask mask(const char* names) { return parse_param_list(names, "test"); }

TEST(PaperTable2, OffsetsFromThreeAndNineSamples) {
  const Geometry actual = section3_actual();
  // Table 2 initial estimates (reference point (210, 245), see test_initial).
  const Geometry start = with_offsets(actual, 1.00913, 0.97689, 1.02748);
  for (int n : {3, 9})
    for (Cost c : {Cost::kJ1, Cost::kJ2, Cost::kML}) expect_recovers(actual, start, mask("dth1,dth2,dth3"), n, c);
}

TEST(PaperTable2, J3RefusesOffsetsWithoutLengths) {
  const Geometry actual = section3_actual();
  const Samples s = paper_samples(actual, 9, 1);
  Problem pb{s.theta_m, with_offsets(actual, 1.00913, 0.97689, 1.02748), mask("dth1,dth2,dth3")};
  LmOptions opt;
  opt.cost = Cost::kJ3;
  EXPECT_THROW(calibrate_lm(pb, opt), InputError);
}

TEST(PaperTable3, OffsetsAndSixLengthsFrom21Samples) {
  const Geometry actual = section3_actual();
  Geometry start = with_offsets(Geometry::gpm2002_nominal(), 1.01052, 0.97614, 1.02659);
  for (int i : {kXa1, kYa1, kXa2, kYa2, kXa3, kYa3}) start[i] = actual[i];  // bases known
  for (Cost c : {Cost::kJ1, Cost::kJ2, Cost::kJ3, Cost::kML})
    expect_recovers(actual, start, mask("dth1,dth2,dth3,la1,la2,la3,lb1,lb2,lb3"), 21, c);
}

Geometry table4_start(const Geometry& actual) {
  Geometry start = with_offsets(Geometry::gpm2002_nominal(), 1.01052, 0.97612, 1.02678);
  for (int i : {kXa1, kYa1, kXa2, kYa2}) start[i] = actual[i];  // the known coordinates
  return start;
}

TEST(PaperTable4, ElevenParametersFrom31Samples) {
  const Geometry actual = section3_actual();
  for (Cost c : {Cost::kJ1, Cost::kJ2, Cost::kJ3, Cost::kML})
    expect_recovers(actual, table4_start(actual), ~mask("xa1,ya1,xa2,ya2"), 31, c);
}

TEST(PaperTable4, TwelveParameterGaugeIsRefusedAsRankDeficient) {
  const Geometry actual = section3_actual();
  const Samples s = paper_samples(actual, 31, 73);
  Problem pb{s.theta_m, table4_start(actual), ~mask("xa1,ya1,ya2")};  // the paper's 3-coordinate gauge
  for (Cost c : {Cost::kJ1, Cost::kJ3, Cost::kML}) {
    LmOptions opt;
    opt.cost = c;
    try {
      calibrate_lm(pb, opt);
      ADD_FAILURE() << "12 free parameters accepted";
    } catch (const InputError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("rank 11 of 12"), std::string::npos) << m;
      EXPECT_NE(m.find("scale and rotation about A1"), std::string::npos) << m;
      EXPECT_NE(m.find("all lengths grow together"), std::string::npos) << m;
      EXPECT_NE(m.find("all offsets shift together"), std::string::npos) << m;
      EXPECT_NE(m.find("fix xa2"), std::string::npos) << m;
      EXPECT_EQ(m.find('\n'), std::string::npos) << "one line";
    }
  }
}

TEST(PaperTable4, TwelveParametersWithAllowRankDeficientLandOnTheFamily) {
  const Geometry actual = section3_actual();
  const Samples s = paper_samples(actual, 31, 73);
  Problem pb{s.theta_m, table4_start(actual), ~mask("xa1,ya1,ya2")};
  LmOptions opt;
  opt.cost = Cost::kML;
  opt.allow_rank_deficient = true;
  pb.true_xy = s.xy;
  const Result r = calibrate_lm(pb, opt);
  EXPECT_TRUE(r.rank_deficient);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.rank, 11);
  ASSERT_FALSE(r.notes.empty());
  EXPECT_NE(r.notes[0].find("minimum-norm"), std::string::npos);
  EXPECT_LT(r.final_cost, 1e-20);  // a perfect fit ...
  // ... of a similar mechanism: all lengths in the same ratio to the actual ones,
  // all offsets shifted by the same angle (docs/EQUATIONS.md).
  const double scale = r.geometry[kLa1] / actual[kLa1];
  const double turn = r.geometry[kDth1] - actual[kDth1];
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(r.geometry[la(i)] / actual[la(i)], scale, 1e-7);
    EXPECT_NEAR(r.geometry[lb(i)] / actual[lb(i)], scale, 1e-7);
    EXPECT_NEAR(r.geometry[dth(i)] - actual[dth(i)], turn, 1e-7);
  }
  EXPECT_TRUE(std::isnan(r.sigma[kLa1])) << "no 1-sigma along an unobservable family";
}

TEST(CalibrateLm, TooFewSamplesIsInputError) {
  const Geometry actual = section3_actual();
  const Samples s = paper_samples(actual, 10, 5);
  Problem pb{s.theta_m, table4_start(actual), default_free_mask()};
  EXPECT_THROW(calibrate_lm(pb, LmOptions{}), InputError);
}

TEST(CalibrateLm, SampleWhoseCirclesDoNotMeetIsNamed) {
  const Geometry actual = section3_actual();
  Samples s = paper_samples(actual, 20, 5);
  s.theta_m[7][1] += 2.0;  // a wild reading
  Problem pb{s.theta_m, table4_start(actual), default_free_mask()};
  try {
    calibrate_lm(pb, LmOptions{});
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("sample 7"), std::string::npos) << e.what();
  }
}

TEST(CalibrateLm, ReportedSigmaEqualsCramerRaoBoundAtTruth) {
  // ML with a given encoder sigma on noiseless data: the solution is the truth
  // and the sandwich covariance must equal the bound sigma^2 (J'J)^-1 (computed
  // independently, without Ceres' covariance).
  const Geometry actual = table5_actual();
  const Robot r = robot_of(actual);
  const Samples s = samples_at(r, disc_poses(r, 50, r.home, 80.0, 9));
  Geometry start = Geometry::gpm2002_nominal();
  for (int i : {kXa1, kYa1, kXa2, kYa2}) start[i] = actual[i];
  for (Cost c : {Cost::kML, Cost::kJ3, Cost::kJ2}) {
    LmOptions opt;
    opt.cost = c;
    opt.encoder_sigma = 1e-4;
    const Result res = calibrate_lm(Problem{s.theta_m, start, default_free_mask()}, opt);
    const auto bound = crb_sigma(actual, default_free_mask(), s.theta_m, 1e-4);
    for (int i = 0; i < kNumParams; ++i) {
      if (!default_free_mask().test(static_cast<size_t>(i))) continue;
      if (c == Cost::kML) {
        EXPECT_NEAR(res.sigma[static_cast<size_t>(i)] / bound[static_cast<size_t>(i)], 1.0, 1e-4) << param_name(i);
      } else {
        // A non-ML cost is no better than the bound, and not much worse here.
        EXPECT_GE(res.sigma[static_cast<size_t>(i)] / bound[static_cast<size_t>(i)], 1.0 - 1e-4) << param_name(i);
        EXPECT_LT(res.sigma[static_cast<size_t>(i)] / bound[static_cast<size_t>(i)], 1.5) << param_name(i);
      }
    }
  }
}

TEST(CalibrateLm, ResidualScaledSigmaMatchesBoundOnNoisyData) {
  // No sigma given: the covariance is scaled by the residual variance; with
  // noise of 1e-4 rad the reported 1-sigma must be the bound within the
  // sampling error of the variance estimate (39 degrees of freedom: ~11%).
  const Geometry actual = table5_actual();
  const Robot r = robot_of(actual);
  const auto poses = disc_poses(r, 50, r.home, 80.0, 9);
  const Samples s = samples_at(r, poses, 1e-4, 2024);
  const Samples clean = samples_at(r, poses);
  Geometry start = Geometry::gpm2002_nominal();
  for (int i : {kXa1, kYa1, kXa2, kYa2}) start[i] = actual[i];
  LmOptions opt;
  opt.cost = Cost::kML;
  const Result res = calibrate_lm(Problem{s.theta_m, start, default_free_mask()}, opt);
  const auto bound = crb_sigma(actual, default_free_mask(), clean.theta_m, 1e-4);
  for (int i = 0; i < kNumParams; ++i) {
    if (!default_free_mask().test(static_cast<size_t>(i))) continue;
    EXPECT_NEAR(res.sigma[static_cast<size_t>(i)] / bound[static_cast<size_t>(i)], 1.0, 0.3) << param_name(i);
  }
}

// The table-5 robot read at 40 disc poses with 1e-4 rad of noise (seed),
// started from the nominal geometry with the frame known.
Problem noisy_disc_problem(unsigned seed) {
  const Geometry actual = table5_actual();
  const Robot r = robot_of(actual);
  const Samples s = samples_at(r, disc_poses(r, 40, r.home, 80.0, 4), 1e-4, seed);
  Geometry start = Geometry::gpm2002_nominal();
  for (int i : {kXa1, kYa1, kXa2, kYa2}) start[i] = actual[i];
  return Problem{s.theta_m, start, default_free_mask()};
}

TEST(CalibrateLm, AnalyticAndAutodiffJacobiansGiveTheSameEstimateOnNoisyData) {
  const Problem p = noisy_disc_problem(77);
  for (Cost c : {Cost::kJ1, Cost::kJ2, Cost::kJ3, Cost::kML}) {
    LmOptions a, d;
    a.cost = d.cost = c;
    d.autodiff = true;
    const Result ra = calibrate_lm(p, a), rd = calibrate_lm(p, d);
    ASSERT_TRUE(ra.converged && rd.converged) << cost_name(c);
    EXPECT_NEAR(ra.final_cost, rd.final_cost, 1e-9 * rd.final_cost) << cost_name(c);
    for (int i = 0; i < kNumParams; ++i) {
      const auto k = static_cast<size_t>(i);
      if (!default_free_mask().test(k)) {
        EXPECT_EQ(ra.geometry[i], rd.geometry[i]) << param_name(i);  // fixed
        continue;
      }
      // The noisy optimum is one point: both reach it to far below its 1-sigma.
      EXPECT_NEAR(ra.geometry[i], rd.geometry[i], 1e-6 * rd.sigma[k]) << cost_name(c) << " " << param_name(i);
      EXPECT_NEAR(ra.sigma[k], rd.sigma[k], 1e-6 * rd.sigma[k]) << cost_name(c) << " " << param_name(i);
    }
  }
}

// A looser function tolerance (the passes of the motion fit use 1e-10)
// stops no later and lands on the same noisy optimum far below its 1-sigma.
TEST(CalibrateLm, ALooserFunctionToleranceStopsSoonerAtTheSameOptimum) {
  const Problem p = noisy_disc_problem(78);
  LmOptions tight, loose;
  loose.function_tolerance = 1e-10;
  const Result rt = calibrate_lm(p, tight), rl = calibrate_lm(p, loose);
  ASSERT_TRUE(rt.converged && rl.converged);
  EXPECT_LT(rl.iterations, rt.iterations);  // the last iterations only polish the rounding
  EXPECT_LE(rl.final_cost, rt.final_cost * (1.0 + 1e-9));
  for (int i = 0; i < kNumParams; ++i) {
    const auto k = static_cast<size_t>(i);
    if (!default_free_mask().test(k)) continue;
    EXPECT_NEAR(rl.geometry[i], rt.geometry[i], 1e-4 * rt.sigma[k]) << param_name(i);
  }
}

// Without the checks (the inner passes of the motion fit) the solve is the
// same to the bit; only the start's analysis and kmrmse are left out.
TEST(CalibrateLm, WithoutTheChecksTheSolveIsTheSame) {
  Problem p = noisy_disc_problem(79);
  p.true_xy.assign(p.theta_m.size(), Eigen::Vector2d(216.5, 250.0));
  LmOptions on, off;
  off.checks = false;
  const Result a = calibrate_lm(p, on), b = calibrate_lm(p, off);
  EXPECT_EQ(a.geometry.values, b.geometry.values);
  EXPECT_EQ(a.final_cost, b.final_cost);
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_EQ(a.rank, 11);
  EXPECT_TRUE(a.kmrmse_mm.has_value());
  EXPECT_EQ(b.rank, 0);  // not analysed
  EXPECT_FALSE(b.kmrmse_mm.has_value());
}

// The error function J at a geometry, summed sample by sample from the
// residual functors (independent of the solver's iteration bookkeeping).
double cost_at(Cost c, const Geometry& g, const std::vector<Eigen::Vector3d>& theta_m) {
  const ParamVector x = to_solver(g, c);
  const double* params[] = {x.data()};
  double ssq = 0.0;
  for (const auto& t : theta_m) {
    std::unique_ptr<ceres::CostFunction> f(make_residual(c, t));
    Eigen::VectorXd r(residual_rows(c));
    f->Evaluate(params, r.data(), nullptr);
    ssq += r.squaredNorm();
  }
  return paper_cost(c, ssq);
}

TEST(CalibrateLm, IterationsRunFromTheStartCostToTheFinalCost) {
  // Every LM iteration is kept (the report's convergence figure): iteration 0
  // at J(start), accepted steps never raise J, the last accepted J is the
  // final cost; both for Ceres' solve and the minimum-norm solve.
  const Geometry actual = section3_actual();
  const Samples s = paper_samples(actual, 31, 73);
  struct Case {
    Cost cost;
    FreeMask free;
    bool rank_deficient;
  };
  for (const Case& k : {Case{Cost::kML, ~mask("xa1,ya1,xa2,ya2"), false}, Case{Cost::kJ3, ~mask("xa1,ya1,xa2,ya2"), false},
                        Case{Cost::kML, ~mask("xa1,ya1,ya2"), true}}) {
    const Problem pb{s.theta_m, table4_start(actual), k.free};
    LmOptions opt;
    opt.cost = k.cost;
    opt.allow_rank_deficient = k.rank_deficient;
    const Result r = calibrate_lm(pb, opt);
    const std::string what = fmt::format("{} rank-deficient {}", cost_name(k.cost), k.rank_deficient);
    ASSERT_GE(r.lm_iterations.size(), 3u) << what;
    EXPECT_EQ(r.lm_iterations.front().iteration, 0) << what;
    EXPECT_EQ(r.lm_iterations.front().step_norm, 0.0) << what;
    EXPECT_NEAR(r.lm_iterations.front().cost, cost_at(k.cost, pb.start, s.theta_m),
                1e-9 * cost_at(k.cost, pb.start, s.theta_m)) << what;
    double last = r.lm_iterations.front().cost;
    for (size_t i = 1; i < r.lm_iterations.size(); ++i) {
      const LmIteration& it = r.lm_iterations[i];
      EXPECT_EQ(it.iteration, static_cast<int>(i)) << what;
      EXPECT_GT(it.step_norm, 0.0) << what << " iteration " << i;
      if (!it.accepted) continue;
      EXPECT_LE(it.cost, last) << what << " iteration " << i;
      last = it.cost;
    }
    EXPECT_NEAR(last, r.final_cost, 1e-9 * r.lm_iterations.front().cost) << what;
    EXPECT_LT(last, 1e-12 * r.lm_iterations.front().cost) << what << ": noiseless data fit exactly";
  }
}

TEST(CalibrateLm, NoisyFitsEndAtTheGaussNewtonFixedPoint) {
  // At the least-squares optimum J'r = 0, so the Gauss-Newton step
  // -(J'J)^-1 J'r computed independently here (QR of the stacked Jacobian
  // of the free parameters, analytic or autodiff as the solver used) is nil:
  // below 1e-8 of each parameter's 1-sigma (s^2 (J'J)^-1, s^2 = sum r^2 /
  // (n - p)), for every cost and both kinds of Jacobian.
  const Geometry actual = table5_actual();
  const Robot r = robot_of(actual);
  const Samples s = samples_at(r, disc_poses(r, 40, r.home, 80.0, 4), 1e-4, 77);
  Geometry start = Geometry::gpm2002_nominal();
  for (int i : {kXa1, kYa1, kXa2, kYa2}) start[i] = actual[i];
  std::vector<int> idx;
  for (int i = 0; i < kNumParams; ++i)
    if (default_free_mask().test(static_cast<size_t>(i))) idx.push_back(i);
  const auto p = static_cast<Eigen::Index>(idx.size());
  for (Cost c : {Cost::kJ1, Cost::kJ2, Cost::kJ3, Cost::kML}) {
    for (bool autodiff : {false, true}) {
      LmOptions o;
      o.cost = c;
      o.autodiff = autodiff;
      const Result res = calibrate_lm(Problem{s.theta_m, start, default_free_mask()}, o);
      ASSERT_TRUE(res.converged) << cost_name(c);
      const ParamVector x = to_solver(res.geometry, c);
      const int rows = residual_rows(c);
      const auto m = static_cast<Eigen::Index>(s.theta_m.size()) * rows;
      Eigen::MatrixXd J(m, p);
      Eigen::VectorXd rv(m);
      Eigen::Matrix<double, Eigen::Dynamic, kNumParams, Eigen::RowMajor> Jj(rows, kNumParams);
      for (size_t j = 0; j < s.theta_m.size(); ++j) {
        std::unique_ptr<ceres::CostFunction> f(autodiff ? make_autodiff_residual(c, s.theta_m[j])
                                                        : make_residual(c, s.theta_m[j]));
        const double* params[] = {x.data()};
        double* jac[] = {Jj.data()};
        ASSERT_TRUE(f->Evaluate(params, rv.data() + static_cast<Eigen::Index>(j) * rows, jac));
        for (Eigen::Index k = 0; k < p; ++k)
          J.block(static_cast<Eigen::Index>(j) * rows, k, rows, 1) = Jj.col(idx[static_cast<size_t>(k)]);
      }
      const Eigen::VectorXd step = J.colPivHouseholderQr().solve(-rv);
      const Eigen::MatrixXd C = (rv.squaredNorm() / static_cast<double>(m - p)) * (J.transpose() * J).inverse();
      for (Eigen::Index k = 0; k < p; ++k) {
        EXPECT_LT(std::abs(step[k]), 1e-8 * std::sqrt(C(k, k)))
            << cost_name(c) << (autodiff ? " autodiff " : " analytic ") << param_name(idx[static_cast<size_t>(k)]);
      }
    }
  }
}

TEST(CalibrateLm, AZeroWeightLeavesTheSampleOutAndAUniformWeightChangesNothing) {
  // Two algorithms for one answer: a corrupted sample at weight 0 against the
  // fit without it; every weight 2 against no weights (the sandwich 1-sigma
  // with the reading noise scales the rows' noise with them).
  const Problem p = noisy_disc_problem(78);
  LmOptions o;
  o.cost = Cost::kML;
  o.encoder_sigma = 1e-4;
  Problem corrupted = p;
  corrupted.theta_m[5][1] += 0.01;
  corrupted.weight.assign(p.theta_m.size(), 1.0);
  corrupted.weight[5] = 0.0;
  Problem without = p;
  without.theta_m.erase(without.theta_m.begin() + 5);
  Problem doubled = p;
  doubled.weight.assign(p.theta_m.size(), 2.0);
  const Result rc = calibrate_lm(corrupted, o), rw = calibrate_lm(without, o), r1 = calibrate_lm(p, o),
               r2 = calibrate_lm(doubled, o);
  for (int i = 0; i < kNumParams; ++i) {
    const auto k = static_cast<size_t>(i);
    if (!default_free_mask().test(k)) continue;
    EXPECT_NEAR(rc.geometry[i], rw.geometry[i], 1e-5 * rw.sigma[k]) << param_name(i);
    EXPECT_NEAR(rc.sigma[k], rw.sigma[k], 1e-5 * rw.sigma[k]) << param_name(i);
    EXPECT_NEAR(r2.geometry[i], r1.geometry[i], 1e-5 * r1.sigma[k]) << param_name(i);
    EXPECT_NEAR(r2.sigma[k], r1.sigma[k], 1e-5 * r1.sigma[k]) << param_name(i);
  }
  Problem wrong = p;
  wrong.weight = {1.0, 1.0};
  EXPECT_THROW(calibrate_lm(wrong, o), InputError);
  wrong.weight.assign(p.theta_m.size(), 1.0);
  wrong.weight[0] = -1.0;
  EXPECT_THROW(calibrate_lm(wrong, o), InputError);
}

}  // namespace
}  // namespace gpm::calib
