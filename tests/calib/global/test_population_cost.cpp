// Population evaluation: independent of thread count and split, equal to the
// single-candidate path.
#include "calib/global/population_cost.hpp"

#include <gtest/gtest.h>

#include "models/errors.hpp"

#include "models/rng.hpp"
#include "calib/paper_values.hpp"
#include "calib/synthetic.hpp"

namespace gpm::calib::global {
namespace {

TEST(PopulationCost, SameValuesForAnyThreadCountSplitAndSinglePath) {
  Robot r;
  r.geometry = table5_actual();
  const Problem p = table5_problem(workspace_samples(r, 50, 3), paper_free_mask());
  const Box box = default_box(Geometry::gpm2002_nominal(), p.free);
  for (Cost cost : {Cost::kJ1, Cost::kJ2, Cost::kJ3}) {
    const PopulationCost one(p, cost, box, 1), two(p, cost, box, 2);
    const int n = one.space().dim();
    const long count = 203;
    std::vector<double> x(static_cast<size_t>(n * count)), f1(count), f2(count), f3(count);
    Rng rng(9);
    for (int k = 0; k < n; ++k)
      for (long c = 0; c < count; ++c) x[k * count + c] = rng.uniform(one.space().lower()[k], one.space().upper()[k]);
    one.evaluate(x.data(), count, count, f1.data());
    two.evaluate(x.data(), count, count, f2.data());
    // Split in two calls at an odd place.
    two.evaluate(x.data(), count, 77, f3.data());
    two.evaluate(x.data() + 77, count, count - 77, f3.data() + 77);
    EXPECT_EQ(f1, f2);
    EXPECT_EQ(f1, f3);
    for (long c = 0; c < count; c += 17) {
      std::vector<double> d(static_cast<size_t>(n));
      for (int k = 0; k < n; ++k) d[k] = x[k * count + c];
      EXPECT_NEAR(one.evaluate_one(d), f1[c], 1e-13 * f1[c]);
    }
  }
}

TEST(PopulationCost, RejectsNoSamplesAndNegativeThreads) {
  Problem p;
  p.start = Geometry::gpm2002_nominal();
  p.free = default_free_mask();
  const Box b = default_box(p.start, p.free);
  EXPECT_THROW(PopulationCost(p, Cost::kJ3, b), gpm::InputError);
  p.theta_m.push_back(Eigen::Vector3d(1, 2, 3));
  EXPECT_THROW(PopulationCost(p, Cost::kJ3, b, -1), gpm::InputError);
}

}  // namespace
}  // namespace gpm::calib::global
