// Tests of report/table_cell.hpp: numbers as a report shows them (significant
// digits in fixed notation, powers of ten in Unicode, values to their 1-sigma).
#include "report/table_cell.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace gpm::report {
namespace {

TEST(TableCell, SignificantDigitsInFixedNotationNeverDropWholeDigits) {
  EXPECT_EQ(sig(9712.3), "9712");
  EXPECT_EQ(sig(9.263), "9.26");
  EXPECT_EQ(sig(0.01274), "0.0127");
  EXPECT_EQ(sig(-2.5e-3, 2), "-0.0025");
  EXPECT_EQ(sig(99.996), "100");   // rounds up a digit: not "100.0"
  EXPECT_EQ(sig(0.99996), "1.00");
  EXPECT_EQ(sig(0.0), "0");
  EXPECT_EQ(sig(-0.0001, 1), "-0.0001");
  EXPECT_EQ(sig(NAN), "-");
}

TEST(TableCell, PowersOfTenOutsideAThousandthToAMillion) {
  EXPECT_EQ(sci(1.05e3), "1050");
  EXPECT_EQ(sci(7.31e-5), "7.31×10⁻⁵");
  EXPECT_EQ(sci(-5.53e-5), "-5.53×10⁻⁵");
  EXPECT_EQ(sci(2.5e7, 2), "2.5×10⁷");
  EXPECT_EQ(sci(9.9996e-5), "1.00×10⁻⁴");  // the mantissa rounds to 10: one power up
  EXPECT_EQ(sci(1e-12, 1), "1×10⁻¹²");
  EXPECT_EQ(sci(INFINITY), "-");
  // The value is read back: mantissa times the power.
  EXPECT_NEAR(7.31 * std::pow(10.0, -5), 7.31e-5, 1e-20);
}

TEST(TableCell, ValuesToATenthOfTheirSigma) {
  EXPECT_EQ(value_to_sigma(244.49751, 1e-3), "244.4975");
  EXPECT_EQ(value_to_sigma(0.0099950, 2e-6), "0.0099950");
  EXPECT_EQ(value_to_sigma(433.0, 0.133), "433.00");
  EXPECT_EQ(value_to_sigma(250.0, NAN), "250");
  EXPECT_EQ(ratio_text(951.98), "952");
  EXPECT_EQ(ratio_text(1.0046), "1.00");
}

}  // namespace
}  // namespace gpm::report
