// solve_global on the paper's section 4.4 problem: DE recovers Table 5 with
// 4 base coordinates fixed; with the paper's 3 fixed it reaches the floor at
// a seed-dependent point and says so.
#include "calib/global/global.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "models/errors.hpp"

#include "calib/paper_values.hpp"
#include "calib/synthetic.hpp"

namespace gpm::calib::global {
namespace {

Problem problem(const FreeMask& free) {
  Robot r;
  r.geometry = table5_actual();
  return table5_problem(workspace_samples(r, 50, 42), free);
}

double max_error(const Geometry& a, const Geometry& b) {
  double e = 0;
  for (int i = 0; i < kNumParams; ++i) e = std::max(e, std::abs(a[i] - b[i]));
  return e;
}

TEST(SolveGlobal, DeOnJ3RecoversTable5ElevenParametersTo1e6) {
  const Problem p = problem(default_free_mask());
  const Result r = solve_global(p, Cost::kJ3, Method::kDE,
                                default_box(Geometry::gpm2002_nominal(), p.free), 1'500'000, 1);
  EXPECT_LE(r.evaluations, 1'500'000);
  EXPECT_LT(r.final_cost, 1e-18);
  EXPECT_LT(max_error(r.geometry, table5_actual()), 1e-6);
  EXPECT_EQ(r.rank, 11);
  EXPECT_FALSE(r.rank_deficient);
  EXPECT_EQ(r.method, "de");
  EXPECT_EQ(r.geometry[kYa2], 0.3);  // fixed at its true value
  ASSERT_FALSE(r.history.empty());
  EXPECT_EQ(r.history.back(), std::make_pair(r.evaluations, r.final_cost));
}

TEST(SolveGlobal, DeThenLmRecoversTable5ElevenParametersTo1e6FromAShortDeRun) {
  const Problem p = problem(default_free_mask());
  const Result r = solve_global(p, Cost::kJ3, Method::kDELM,
                                default_box(Geometry::gpm2002_nominal(), p.free), 100'000, 3);
  EXPECT_EQ(r.method, "de+lm");
  EXPECT_GT(r.evaluations, 100'000);  // DE's budget plus LM's own evaluations
  EXPECT_LT(max_error(r.geometry, table5_actual()), 1e-6);
  EXPECT_LT(r.final_cost, 1e-17);
  EXPECT_TRUE(r.converged);
}

TEST(SolveGlobal, DeThenLmRefusesThePaperRankDeficientSetUnlessAllowed) {
  const Problem p = problem(paper_free_mask());
  const Box box = default_box(Geometry::gpm2002_nominal(), p.free);
  EXPECT_THROW(solve_global(p, Cost::kJ3, Method::kDELM, box, 20'000, 1), gpm::InputError);
  GlobalOptions o;
  o.budget = 20'000;
  o.allow_rank_deficient = true;
  const Result r = solve_global(p, Cost::kJ3, Method::kDELM, box, o);
  EXPECT_TRUE(r.rank_deficient);
  EXPECT_EQ(r.rank, 11);
}

TEST(SolveGlobal, PaperTwelveParametersReachTheFloorAtSeedDependentPoints) {
  const Problem p = problem(paper_free_mask());
  const Box box = default_box(Geometry::gpm2002_nominal(), p.free);
  const Result a = solve_global(p, Cost::kJ3, Method::kDE, box, 1'500'000, 1);
  const Result b = solve_global(p, Cost::kJ3, Method::kDE, box, 1'500'000, 2);
  for (const Result* r : {&a, &b}) {
    EXPECT_LT(r->final_cost, 1e-16);  // a perfect fit ...
    EXPECT_EQ(r->rank, 11);           // ... of a rank-deficient problem
    EXPECT_TRUE(r->rank_deficient);
    ASSERT_FALSE(r->notes.empty());
    EXPECT_NE(r->notes[0].find("rank 11 of 12"), std::string::npos);
  }
  // Different seeds, different points of the similarity family.
  EXPECT_GT(max_error(a.geometry, b.geometry), 1e-3);
}

TEST(SolveGlobal, SameSeedSameResultWhateverTheThreadCount) {
  const Problem p = problem(default_free_mask());
  const Box box = default_box(Geometry::gpm2002_nominal(), p.free);
  for (Method m : {Method::kGA, Method::kPSO, Method::kDE}) {
    GlobalOptions o1;
    o1.budget = 20'000;
    o1.seed = 5;
    o1.threads = 1;
    GlobalOptions o2 = o1;
    o2.threads = 2;
    const Result a = solve_global(p, Cost::kJ1, m, box, o1);
    const Result b = solve_global(p, Cost::kJ1, m, box, o2);
    EXPECT_EQ(a.geometry, b.geometry) << method_name(m);
    EXPECT_EQ(a.final_cost, b.final_cost);
    EXPECT_EQ(a.history, b.history);
    EXPECT_EQ(a.evaluations, 20'000);
  }
}

TEST(SolveGlobal, BadInput) {
  const Problem p = problem(default_free_mask());
  const Box box = default_box(Geometry::gpm2002_nominal(), p.free);
  EXPECT_THROW(solve_global(p, Cost::kJ3, Method::kDE, box, 0, 1), gpm::InputError);
  EXPECT_THROW(solve_global(p, Cost::kML, Method::kDE, box, 100, 1), gpm::InputError);
  EXPECT_THROW(solve_global(p, Cost::kJ3, Method::kLM, box, 100, 1), gpm::InputError);
}

}  // namespace
}  // namespace gpm::calib::global
