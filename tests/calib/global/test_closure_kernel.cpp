// Tests of calib/global/closure_kernel.cpp: the vectorised kernel against
// scalar J1, J2, J3 written from the paper's equations, against the templated
// closure of models/closure.hpp on random parameter sets and readings, and
// (through PopulationCost) against the Ceres residuals of calib/residuals.hpp
// on the same data; the floor of J3 at the true parameters.
#include "calib/global/closure_kernel.hpp"

#include <memory>

#include <gtest/gtest.h>

#include "models/errors.hpp"

#include "calib/global/population_cost.hpp"
#include "calib/parameterization.hpp"
#include "calib/residuals.hpp"
#include "models/closure.hpp"
#include "models/rng.hpp"
#include "calib/paper_values.hpp"
#include "calib/synthetic.hpp"
#include "models/kinematics.hpp"
#include "tests/calib/global/reference_costs.hpp"

namespace gpm::calib::global::testing {
namespace {

Samples table5_samples() {
  Robot r;
  r.geometry = table5_actual();
  return workspace_samples(r, 50, 42);
}

// A geometry drawn uniformly in the Table 5 box (all 15 parameters perturbed).
Geometry random_geometry(Rng& rng) {
  Geometry g = Geometry::gpm2002_nominal();
  for (int p = 0; p < kNumParams; ++p) g[p] += is_offset(p) ? rng.uniform(-0.2, 0.2) : rng.uniform(-5, 5);
  return g;
}

TEST(ReferenceFk, MatchesTheModelsForwardKinematics) {
  // Guards the test's own reference against the models library.
  const Geometry g = table5_actual();
  const Samples s = table5_samples();
  for (size_t j = 0; j < 5; ++j) {
    const Eigen::Vector3d ta = active_from_readings(g, s.theta_m[j]);
    const auto B = elbows(g, ta);
    const double xb[3] = {B[0].x(), B[1].x(), B[2].x()}, yb[3] = {B[0].y(), B[1].y(), B[2].y()};
    const double lb[3] = {g[kLb1], g[kLb2], g[kLb3]};
    EXPECT_NEAR((reference_fk(xb, yb, lb) - s.xy[j]).norm(), 0.0, 1e-9);
  }
}

// All 15 parameters free, starting at nominal.
Problem all_free_problem(const Samples& s) {
  Problem p;
  p.theta_m = s.theta_m;
  p.start = Geometry::gpm2002_nominal();
  p.free.set();
  return p;
}

// Batch values over many random all-free geometries equal the references.
TEST(ClosureKernel, BatchEqualsScalarReferencesTo1e12) {
  const Samples s = table5_samples();
  const Problem p = all_free_problem(s);
  const Box box = default_box(Geometry::gpm2002_nominal(), p.free);
  Rng rng(5);
  const long count = 37;  // not a multiple of the kernel block
  std::vector<Geometry> geoms;
  for (long c = 0; c < count; ++c) geoms.push_back(random_geometry(rng));
  for (Cost cost : {Cost::kJ1, Cost::kJ2, Cost::kJ3}) {
    const PopulationCost pc(p, cost, box, 2);
    const int n = pc.space().dim();
    ASSERT_EQ(n, 15);
    std::vector<double> x(static_cast<size_t>(n * count)), f(static_cast<size_t>(count));
    for (long c = 0; c < count; ++c) {
      const auto d = pc.space().from_geometry(geoms[c]);
      for (int k = 0; k < n; ++k) x[k * count + c] = d[k];
    }
    pc.evaluate(x.data(), count, count, f.data());
    for (long c = 0; c < count; ++c) {
      const Geometry& g = geoms[c];
      double ref = 0;
      if (cost == Cost::kJ1) ref = reference_j1(s.theta_m, g);
      if (cost == Cost::kJ2) ref = reference_j2(s.theta_m, g);
      if (cost == Cost::kJ3) {
        double lac[3], las[3];
        for (int i = 0; i < 3; ++i) {
          lac[i] = x[(kLa1 + i) * count + c];  // J3 searches lac_i in la_i's place
          las[i] = x[(kDth1 + i) * count + c];
        }
        EXPECT_DOUBLE_EQ(lac[0] * lac[0] + las[0] * las[0] + 0.0,
                         std::pow(std::hypot(lac[0], las[0]), 2));
        ref = reference_j3(s.theta_m, g, lac, las);
      }
      EXPECT_GT(ref, 1.0);  // far from the optimum: a meaningful comparison
      EXPECT_NEAR(f[c], ref, 1e-12 * ref) << cost_name(cost) << " candidate " << c;
    }
  }
}

// J1 and J2/J3 of one candidate (kernel variables kv) from models/closure.hpp:
// e_i = |O - B_i|^2 - lb_i^2 and |E1 row i| = |O - B_i| - lb_i per sample.
double closure_cost(Cost cost, const std::vector<Eigen::Vector3d>& theta_m, const double* kv) {
  Geometry x;  // the decoupled layout: l_ac in la's slot, l_as in dth's
  for (int i = 0; i < 3; ++i) {
    x[xa(i)] = kv[kKxa1 + 2 * i];
    x[ya(i)] = kv[kKya1 + 2 * i];
    x[la(i)] = kv[kKlac1 + i];
    x[dth(i)] = kv[kKlas1 + i];
    x[lb(i)] = kv[kKlb1 + i];
  }
  double J = 0.0;
  for (const Eigen::Vector3d& t : theta_m) {
    const Closure<double> c = closure(x.values.data(), t.data(), true, false);
    EXPECT_TRUE(c.ok);
    for (int i = 0; i < 3; ++i) {
      const double r = std::hypot(c.Ox - c.Bx[i], c.Oy - c.By[i]);
      const double e = cost == Cost::kJ1 ? r - x[lb(i)] : r * r - x[lb(i)] * x[lb(i)];
      J += e * e;
    }
  }
  return J;
}

TEST(ClosureKernel, BlockEqualsTheTemplatedClosureOnRandomParametersAndReadingsTo1e12) {
  Rng rng(2027);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Eigen::Vector3d> tm;
    for (int j = 0; j < 30; ++j)  // readings around home (1.111, 3.111, 4.825 rad)
      tm.emplace_back(1.111 + rng.uniform(-0.4, 0.4), 3.111 + rng.uniform(-0.4, 0.4), 4.825 + rng.uniform(-0.4, 0.4));
    const SampleTable t = make_sample_table(tm);
    std::vector<double> kv(kNumKernelVars * kKernelBlock);
    for (int c = 0; c < kKernelBlock; ++c) {
      const Geometry g = random_geometry(rng);
      for (int i = 0; i < 3; ++i) {
        kv[(kKxa1 + 2 * i) * kKernelBlock + c] = g[xa(i)];
        kv[(kKya1 + 2 * i) * kKernelBlock + c] = g[ya(i)];
        kv[(kKlac1 + i) * kKernelBlock + c] = g[la(i)] * std::cos(g[dth(i)]);
        kv[(kKlas1 + i) * kKernelBlock + c] = g[la(i)] * std::sin(g[dth(i)]);
        kv[(kKlb1 + i) * kKernelBlock + c] = g[lb(i)];
      }
    }
    for (Cost cost : {Cost::kJ1, Cost::kJ2, Cost::kJ3}) {
      double J[kKernelBlock];
      closure_cost_block(cost, t, kv.data(), J);
      for (int c = 0; c < kKernelBlock; ++c) {
        double one[kNumKernelVars];
        for (int v = 0; v < kNumKernelVars; ++v) one[v] = kv[v * kKernelBlock + c];
        const double ref = closure_cost(cost, tm, one);
        EXPECT_GT(ref, 1e-3);  // far from a perfect fit: a meaningful comparison
        EXPECT_NEAR(J[c], ref, 1e-12 * ref) << cost_name(cost) << " trial " << trial << " candidate " << c;
        EXPECT_NEAR(closure_cost_single(cost, t, one), ref, 1e-12 * ref);
      }
    }
  }
}

// The batch J1, J2, J3 equal the paper's J from the Ceres residuals (sum of
// squares of make_residual's rows, paper_cost) at the same parameters.
TEST(ClosureKernel, BatchCostsEqualTheCeresResidualCosts) {
  const Samples s = table5_samples();
  const Problem p = all_free_problem(s);
  const Box box = default_box(Geometry::gpm2002_nominal(), p.free);
  Rng rng(77);
  for (Cost cost : {Cost::kJ1, Cost::kJ2, Cost::kJ3}) {
    const PopulationCost pc(p, cost, box, 1);
    for (int trial = 0; trial < 10; ++trial) {
      const Geometry g = trial == 0 ? table5_actual() : random_geometry(rng);
      const ParamVector x = to_solver(g, cost);
      double ss = 0.0;
      for (const Eigen::Vector3d& t : s.theta_m) {
        std::unique_ptr<ceres::CostFunction> f(make_residual(cost, t));
        double r[6];
        const double* params[] = {x.data()};
        ASSERT_TRUE(f->Evaluate(params, r, nullptr));
        for (int k = 0; k < residual_rows(cost); ++k) ss += r[k] * r[k];
      }
      const double ceres_J = paper_cost(cost, ss);
      const double batch_J = pc.evaluate_one(pc.space().from_geometry(g));
      if (trial == 0) {
        EXPECT_LT(batch_J, 1e-17) << cost_name(cost);  // both at the floating-point floor
        EXPECT_LT(ceres_J, 1e-17) << cost_name(cost);
      } else {
        EXPECT_NEAR(batch_J, ceres_J, 1e-10 * ceres_J) << cost_name(cost) << " trial " << trial;
      }
    }
  }
}

TEST(ClosureKernel, J2EqualsJ3AtTheSameMechanism) {
  // Same mechanism, coupled vs decoupled variables: same closure (docs/EQUATIONS.md).
  const Samples s = table5_samples();
  Problem p = table5_problem(s, default_free_mask());
  const Box box = default_box(Geometry::gpm2002_nominal(), p.free);
  const PopulationCost j2(p, Cost::kJ2, box, 1), j3(p, Cost::kJ3, box, 1);
  const Geometry g = Geometry::gpm2002_nominal();
  const double a = j2.evaluate_one(j2.space().from_geometry(g));
  const double b = j3.evaluate_one(j3.space().from_geometry(g));
  EXPECT_GT(a, 1e3);
  EXPECT_NEAR(a, b, 1e-12 * a);
}

TEST(ClosureKernel, J3AtTheActualParametersIsAtTheFloatingPointFloor) {
  const Samples s = table5_samples();
  const Problem p = table5_problem(s, default_free_mask());
  const PopulationCost pc(p, Cost::kJ3, default_box(Geometry::gpm2002_nominal(), p.free), 1);
  const double at_actual = pc.evaluate_one(pc.space().from_geometry(table5_actual()));
  EXPECT_LT(at_actual, 1e-17);  // docs/EQUATIONS.md: about 1e-19 for 50 samples
  // 1 micrometre off in one length is visible far above the floor.
  Geometry off = table5_actual();
  off[kLb2] += 1e-3;
  EXPECT_GT(pc.evaluate_one(pc.space().from_geometry(off)), 1e-6);
  // ...and so is the nominal geometry (paper section 4.5 reports J3 ~ 1e5 there on its data).
  EXPECT_GT(pc.evaluate_one(pc.space().from_geometry(Geometry::gpm2002_nominal())), 1e2);
}

TEST(ClosureKernel, CollinearElbowsGiveInfinity) {
  SampleTable t = make_sample_table({Eigen::Vector3d(0, 0, 0)});
  double kv[kNumKernelVars] = {};
  for (int i = 0; i < 3; ++i) kv[kKlb1 + i] = 1.0;  // all elbows at the origin
  EXPECT_EQ(closure_cost_single(Cost::kJ2, t, kv), std::numeric_limits<double>::infinity());
  EXPECT_THROW(closure_cost_single(Cost::kML, t, kv), gpm::InputError);
}

}  // namespace
}  // namespace gpm::calib::global::testing
