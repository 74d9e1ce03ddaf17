// Tests of models/samples.cpp: the CSV contract, exact round trip (with the
// optional times and drive torques), bad input.
#include "models/samples.hpp"

#include <gtest/gtest.h>

#include "models/errors.hpp"

namespace gpm {
namespace {

std::string error_of(const std::string& text) {
  try {
    parse_samples_csv(text, "s.csv");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Samples, ColumnsFoundByNameOthersIgnored) {
  const Samples s = parse_samples_csv("note,theta_m3,sample,theta_m1,theta_m2\nx,3,7,1,2\n", "s.csv");
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s.theta_m[0], Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(s.id[0], 7);
  EXPECT_FALSE(s.has_xy);
}

TEST(Samples, RoundTripExact) {
  Samples s;
  s.has_xy = true;
  for (int j = 0; j < 50; ++j) {
    s.id.push_back(j);
    s.theta_m.emplace_back(1.0 / (j + 3), std::sqrt(2.0) * j, -0.1 * j);
    s.xy.emplace_back(216.5 + 1.0 / 3.0 * j, 250 - j * 0.7);
  }
  const Samples b = parse_samples_csv(samples_to_csv(s), "t");
  ASSERT_EQ(b.size(), s.size());
  for (size_t j = 0; j < s.size(); ++j) {
    EXPECT_EQ(b.theta_m[j], s.theta_m[j]);
    EXPECT_EQ(b.xy[j], s.xy[j]);
  }
}

TEST(Samples, TimesAndTorquesRoundTripExact) {
  Samples s;
  for (int j = 0; j < 20; ++j) {
    s.id.push_back(j);
    s.theta_m.emplace_back(1.0 / (j + 3), std::sqrt(2.0) * j, -0.1 * j);
    s.t.push_back(static_cast<double>(j) * (4 / 4000.0));
    s.tau.emplace_back(0.1 * j, -1.0 / (j + 7), 3.0);
    s.tau_last.emplace_back(std::sqrt(3.0) * j, 0.0, -2.5);
    s.tau_between.emplace_back(1.0 / 7.0, j * 1e-17, -0.0);
  }
  const std::string text = samples_to_csv(s);
  EXPECT_EQ(text.substr(0, text.find('\n')),
            "sample,theta_m1,theta_m2,theta_m3,tau1,tau2,tau3,tau_last1,tau_last2,tau_last3,tau_between1,tau_between2,"
            "tau_between3,t");
  const Samples b = parse_samples_csv(text, "t");
  ASSERT_EQ(b.size(), s.size());
  EXPECT_EQ(b.t, s.t);
  EXPECT_EQ(b.tau, s.tau);
  EXPECT_EQ(b.tau_last, s.tau_last);
  EXPECT_EQ(b.tau_between, s.tau_between);
  // Without them (an old file) they stay empty.
  const Samples old = parse_samples_csv("sample,theta_m1,theta_m2,theta_m3\n0,1,2,3\n", "s.csv");
  EXPECT_TRUE(old.t.empty() && old.tau.empty() && old.tau_last.empty() && old.tau_between.empty());
}

TEST(Samples, BadTimesAndTorquesNameLineAndColumn) {
  const std::string head = "sample,theta_m1,theta_m2,theta_m3,t,tau_last1,tau_last2,tau_last3\n";
  EXPECT_EQ(error_of(head + "0,1,2,3,0,1,2,3\n1,1,2,3,0.001,1,x,3\n"),
            "s.csv:3: column 'tau_last2': 'x' is not a number");
  EXPECT_EQ(error_of(head + "0,1,2,3,inf,1,2,3\n"), "s.csv:2: column 't': value must be finite, got 'inf'");
  EXPECT_EQ(error_of(head + "0,1,2,3,0.002,1,2,3\n1,1,2,3,0.001,1,2,3\n"),
            "s.csv:3: column 't': 0.001 s does not follow 0.002 s of the row before (the times of the readings "
            "must increase)");
  EXPECT_EQ(error_of("theta_m1,theta_m2,theta_m3,tau_between1,tau_between3\n1,2,3,4,5\n"),
            "s.csv:1: column 'tau_between2' missing (give tau_between1,tau_between2,tau_between3 all three, or none)");
}

TEST(Samples, BadInputNamesLineAndColumn) {
  EXPECT_EQ(error_of("sample,theta_m1,theta_m2\n"),
            "s.csv:1: missing column 'theta_m3' (the header must name theta_m1,theta_m2,theta_m3; "
            "sample, x, y are optional)");
  EXPECT_EQ(error_of("sample,theta_m1,theta_m2,theta_m3\n0,1,2,3\n1,1,zz,3\n"),
            "s.csv:3: column 'theta_m2': 'zz' is not a number");
  EXPECT_EQ(error_of("sample,theta_m1,theta_m2,theta_m3\n0,1,nan,3\n"),
            "s.csv:2: column 'theta_m2': value must be finite, got 'nan'");
  EXPECT_NE(error_of("sample,theta_m1,theta_m2,theta_m3\n0,1,2\n").find("column 'theta_m3' is missing"),
            std::string::npos);
  EXPECT_NE(error_of("theta_m1,theta_m2,theta_m3,x\n1,2,3,4\n").find("give both x and y"),
            std::string::npos);
  EXPECT_NE(error_of("").find("empty file"), std::string::npos);
  // Found by fuzzing: a sample id beyond the range of long.
  EXPECT_NE(error_of("sample,theta_m1,theta_m2,theta_m3\n2222222222222222222222222,1,2,3\n")
                .find("column 'sample'"),
            std::string::npos);
}

TEST(Samples, RowWithExtraFieldRefused) {
  // A decimal comma in the last column: 5 fields under a 4-field header.
  EXPECT_EQ(error_of("sample,theta_m1,theta_m2,theta_m3\n0,1,2,3\n1,1,2,1,5\n"),
            "s.csv:3: expected 4 fields as in the header (line 1), found 5 (a decimal comma or an "
            "extra field?)");
  // Empty trailing fields count too (a trailing comma is one more field).
  EXPECT_NE(error_of("sample,theta_m1,theta_m2,theta_m3\n0,1,2,3,\n").find("found 5"),
            std::string::npos);
  // A short row is refused even when the missing field is one the reader ignores.
  EXPECT_EQ(error_of("sample,theta_m1,theta_m2,theta_m3,note\n0,1,2,3\n"),
            "s.csv:2: expected 5 fields as in the header (line 1), found 4 (column 'note' is "
            "missing on this row)");
}

TEST(Samples, ColumnNamedTwiceRefused) {
  // Issue 36.5: the first theta_m1 used to win silently.
  EXPECT_EQ(error_of("sample,theta_m1,theta_m2,theta_m3,theta_m1\n0,1,2,3,4\n"),
            "s.csv:1: column 'theta_m1' appears twice in the header (fields 2 and 5); a column may appear "
            "once: keep one of the two");
  // Also for a column the reader ignores.
  EXPECT_NE(error_of("note,theta_m1,theta_m2,theta_m3,note\na,1,2,3,b\n").find("column 'note' appears twice"),
            std::string::npos);
}

TEST(Samples, SampleIdTwiceRefused) {
  // Issue 36: a file joined from two sessions used to be calibrated with both copies.
  EXPECT_EQ(error_of("sample,theta_m1,theta_m2,theta_m3\n0,1,2,3\n1,1,2,3\n0,1,2,4\n"),
            "s.csv:4: sample 0 appears twice (first at line 2): each sample is one row; the file was edited or "
            "joined from others");
  // Without a sample column the ids are the row indices: never twice.
  EXPECT_EQ(error_of("theta_m1,theta_m2,theta_m3\n1,2,3\n1,2,3\n"), "");
}

}  // namespace
}  // namespace gpm
