// The decision vector of each cost, its box, and the mapping to the 15 parameters.
#include "calib/global/decision_space.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "models/errors.hpp"

#include "calib/paper_values.hpp"
#include "calib/synthetic.hpp"

namespace gpm::calib::global {
namespace {

TEST(DefaultBox, IsPaperTable5ForTheNominalGpm2002) {
  const Box b = default_box(Geometry::gpm2002_nominal(), paper_free_mask());
  // Table 5 X_min / X_max.
  EXPECT_EQ(b.lower[kYa2], -5);  EXPECT_EQ(b.upper[kYa2], 5);
  EXPECT_EQ(b.lower[kXa3], 428); EXPECT_EQ(b.upper[kXa3], 438);
  EXPECT_EQ(b.lower[kYa3], 495); EXPECT_EQ(b.upper[kYa3], 505);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(b.lower[la(i)], 239); EXPECT_EQ(b.upper[la(i)], 249);
    EXPECT_EQ(b.lower[lb(i)], 239); EXPECT_EQ(b.upper[lb(i)], 249);
    EXPECT_EQ(b.lower[dth(i)], -0.2); EXPECT_EQ(b.upper[dth(i)], 0.2);
  }
  // Fixed ones: zero width at nominal.
  EXPECT_EQ(b.lower[kXa2], 433); EXPECT_EQ(b.upper[kXa2], 433);
  // Free coordinates outside Table 5: nominal +- 5 mm.
  FreeMask all;
  all.set();
  const Box c = default_box(Geometry::gpm2002_nominal(), all);
  EXPECT_EQ(c.lower[kXa2], 428);
  EXPECT_EQ(c.upper[kYa1], 255);
}

TEST(DecisionSpace, J1J2SearchTheParametersThemselves) {
  Problem p;
  p.start = table5_actual();
  p.free = paper_free_mask();
  const DecisionSpace s(p, Cost::kJ2, default_box(Geometry::gpm2002_nominal(), p.free));
  ASSERT_EQ(s.dim(), 12);
  EXPECT_EQ(s.names().front(), "ya2");
  EXPECT_EQ(s.names().back(), "dth3");
  EXPECT_FALSE(s.decoupled(0));
}

TEST(DecisionSpace, J3SearchesDecoupledVariablesOverTheSectorsBoundingBox) {
  Problem p;
  p.start = table5_actual();
  p.free = default_free_mask();
  const DecisionSpace s(p, Cost::kJ3, default_box(Geometry::gpm2002_nominal(), p.free));
  ASSERT_EQ(s.dim(), 11);
  EXPECT_EQ(s.names()[2], "lac1");  // xa3 ya3 then lac1..3 lb1..3 las1..3
  EXPECT_EQ(s.names()[10], "las3");
  EXPECT_TRUE(s.decoupled(2));
  // l_ac in [239 cos 0.2, 249], l_as in [-249 sin 0.2, 249 sin 0.2].
  EXPECT_DOUBLE_EQ(s.lower()[2], 239 * std::cos(0.2));
  EXPECT_DOUBLE_EQ(s.upper()[2], 249.0);
  EXPECT_DOUBLE_EQ(s.lower()[8], -249 * std::sin(0.2));
  EXPECT_DOUBLE_EQ(s.upper()[8], 249 * std::sin(0.2));
  // Every corner of the paper's (la, dth) box lies in the decision box.
  for (double l : {239.0, 249.0})
    for (double t : {-0.2, 0.0, 0.2}) {
      EXPECT_GE(l * std::cos(t), s.lower()[2] - 1e-12);
      EXPECT_LE(l * std::cos(t), s.upper()[2] + 1e-12);
      EXPECT_GE(l * std::sin(t), s.lower()[8] - 1e-12);
      EXPECT_LE(l * std::sin(t), s.upper()[8] + 1e-12);
    }
}

TEST(DecisionSpace, RoundTripsAndKeepsFixedValues) {
  Problem p;
  p.start = table5_actual();
  p.start[kYa2] = 0.3;
  p.free = default_free_mask();
  for (Cost c : {Cost::kJ1, Cost::kJ2, Cost::kJ3}) {
    const DecisionSpace s(p, c, default_box(Geometry::gpm2002_nominal(), p.free));
    Geometry g = table5_actual();
    g[kXa3] = 431.25;
    g[kDth2] = 0.123;
    const Geometry back = s.to_geometry(s.from_geometry(g));
    for (int i = 0; i < kNumParams; ++i) EXPECT_NEAR(back[i], g[i], 1e-12) << param_name(i);
    EXPECT_EQ(back[kYa2], 0.3);
  }
}

TEST(DecisionSpace, OnlyOneOfLaDthFreeKeepsTheCoupledVariable) {
  Problem p;
  p.start = Geometry::gpm2002_nominal();
  p.free.set(kLa1);
  p.free.set(kDth2);
  const DecisionSpace s(p, Cost::kJ3, default_box(Geometry::gpm2002_nominal(), p.free));
  EXPECT_FALSE(s.decoupled(0));
  EXPECT_FALSE(s.decoupled(1));
  EXPECT_EQ(s.names(), (std::vector<std::string>{"la1", "dth2"}));
}

TEST(DecisionSpace, RejectsBadInput) {
  Problem p;
  p.start = Geometry::gpm2002_nominal();
  p.free = default_free_mask();
  Box b = default_box(Geometry::gpm2002_nominal(), p.free);
  EXPECT_THROW(DecisionSpace(p, Cost::kML, b), gpm::InputError);
  b.upper[kLb1] = b.lower[kLb1];
  EXPECT_THROW(DecisionSpace(p, Cost::kJ3, b), gpm::InputError);
  p.free.reset();
  EXPECT_THROW(DecisionSpace(p, Cost::kJ3, default_box(p.start, p.free)), gpm::InputError);
}

}  // namespace
}  // namespace gpm::calib::global
