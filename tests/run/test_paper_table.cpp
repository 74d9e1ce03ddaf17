// Tests of run/paper/paper_table.cpp: printed precision, the agree/differ
// decision of a row against the printed value, value formatting.
#include <gtest/gtest.h>

#include "run/paper/paper_table.hpp"

namespace gpm::paper {
namespace {

TEST(PrintedHalfUnit, HandWorkedCases) {
  EXPECT_DOUBLE_EQ(printed_half_unit("1.00078"), 5e-6);
  EXPECT_DOUBLE_EQ(printed_half_unit("244.1"), 0.05);
  EXPECT_DOUBLE_EQ(printed_half_unit("34"), 0.5);
  EXPECT_DOUBLE_EQ(printed_half_unit("3.1841e2"), 5e-3);   // 318.41: last digit 0.01
  EXPECT_DOUBLE_EQ(printed_half_unit("1.0211e-4"), 5e-9);  // 0.00010211
  EXPECT_DOUBLE_EQ(printed_half_unit("(empty)"), 0.0);
}

TEST(CompareRow, AgreesWithinThePrintedDigitsOnly) {
  const Row same = compare_row("dth1", "rad", "1.00000", 1.000004, Reason::kMethod, "why");
  EXPECT_EQ(same.reason, Reason::kAgrees);
  EXPECT_TRUE(same.why.empty());
  const Row off = compare_row("dth1", "rad", "1.00000", 1.000006, Reason::kMethod, "the solver stopped");
  EXPECT_EQ(off.reason, Reason::kMethod);
  EXPECT_EQ(off.why, "the solver stopped");
  ASSERT_TRUE(off.paper && off.ours);
  EXPECT_DOUBLE_EQ(*off.paper, 1.0);
  // An absolute tolerance wider than the printed digits.
  EXPECT_EQ(compare_row("x", "", "1.0", 1.3, Reason::kOpen, "w", 0.5).reason, Reason::kAgrees);
  // A non-finite value never agrees.
  EXPECT_EQ(compare_row("x", "", "1.0", NAN, Reason::kOpen, "w").reason, Reason::kOpen);
}

TEST(FormatValue, SixSignificantDigitsOrExponent) {
  EXPECT_EQ(format_value(244.1), "244.1");
  EXPECT_EQ(format_value(1.0), "1");
  EXPECT_EQ(format_value(0.0), "0");
  EXPECT_EQ(format_value(3.5946e-20), "3.59460e-20");
  EXPECT_EQ(format_value(1.27239e7), "1.27239e+07");
  EXPECT_EQ(format_value(-0.0334), "-0.0334");
}

}  // namespace
}  // namespace gpm::paper
