// Tests of models/parameters.cpp: names, indices, suggestions, --fix lists.
#include "models/parameters.hpp"

#include <gtest/gtest.h>

#include "models/errors.hpp"

namespace gpm {
namespace {

TEST(Parameters, NamesAndIndicesRoundTrip) {
  for (int i = 0; i < kNumParams; ++i) EXPECT_EQ(param_index(param_name(i)), i);
  EXPECT_EQ(param_name(kLb2), "lb2");
  EXPECT_FALSE(param_index("xb1"));
}

TEST(Parameters, NearestNameSuggestion) {
  EXPECT_EQ(nearest_param_name("xb1"), "xa1");
  EXPECT_EQ(nearest_param_name("dth4"), "dth1");
  EXPECT_EQ(nearest_param_name("LA2"), "la2");
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3);
}

TEST(Parameters, ParseListAndDefaultGauge) {
  const FreeMask fixed = parse_param_list("xa1, ya1,xa2,ya2", "--fix");
  EXPECT_EQ(fixed.count(), 4u);
  EXPECT_EQ((~fixed), default_free_mask());
  EXPECT_EQ(format_param_list(fixed), "xa1,ya1,xa2,ya2");
  EXPECT_EQ(default_free_mask().count(), 11u);
  try {
    parse_param_list("xa1,ya1,xb1", "calibration.fix");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "calibration.fix[2]: unknown parameter 'xb1' (did you mean xa1?); valid: xa1 ya1 "
                 "xa2 ya2 xa3 ya3 la1 la2 la3 lb1 lb2 lb3 dth1 dth2 dth3");
  }
}

TEST(Parameters, ParseListRefusesAParameterGivenTwice) {
  // Issue 36.12: --fix xa1,xa1 was taken as one fixed parameter.
  try {
    parse_param_list("xa1,ya1, xa1", "--fix");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "--fix[2]: 'xa1' is given twice; give each parameter once");
  }
}

TEST(Parameters, KindsAndNominal) {
  const Geometry g = Geometry::gpm2002_nominal();
  EXPECT_EQ(g.A(2), Eigen::Vector2d(433, 500));
  EXPECT_TRUE(is_length(kLa1));
  EXPECT_TRUE(is_length(kLb3));
  EXPECT_FALSE(is_length(kDth1));
  EXPECT_TRUE(is_offset(kDth3));
  EXPECT_FALSE(is_offset(kYa3));
}

}  // namespace
}  // namespace gpm
