// Tests of calib/play_crossing.cpp: the samples in which a passive link may
// be crossing its play, worked by hand on short force sequences.
#include "calib/play_crossing.hpp"

#include <gtest/gtest.h>

namespace gpm::calib {
namespace {

// Chain i's marks of a result, as a string of 0 and 1 (sample by sample).
std::string marks(const std::vector<std::array<bool, 3>>& m, int i) {
  std::string s;
  for (const auto& a : m) s += a[static_cast<std::size_t>(i)] ? '1' : '0';
  return s;
}

// Forces of chain 0 from a list, chains 1 and 2 constant at +2 N.
std::vector<std::optional<Eigen::Vector3d>> chain0(const std::vector<double>& T) {
  std::vector<std::optional<Eigen::Vector3d>> out;
  for (double t : T) out.push_back(Eigen::Vector3d(t, 2.0, 2.0));
  return out;
}

// Each sign change marks its first sample and the window's others after it;
// a force that keeps its sign, however small, marks none.
TEST(PlayCrossing, MarksTheWindowFromEachSignChange) {
  const auto t = chain0({3.0, 2.0, 0.1, -0.1, -1.0, -2.0, -3.0, -3.0, 1.0, 2.0});
  const auto m = play_crossing(t, 3);
  EXPECT_EQ(marks(m, 0), "0001110011");
  EXPECT_EQ(marks(m, 1), "0000000000");
  EXPECT_EQ(marks(m, 2), "0000000000");
}

// A change within the window of the one before starts the window again.
TEST(PlayCrossing, AChangeWithinTheWindowRestartsIt) {
  const auto t = chain0({1.0, -1.0, 1.0, 1.0, 1.0, 1.0, 1.0});
  EXPECT_EQ(marks(play_crossing(t, 2), 0), "0111000");
}

// Unknown forces neither start nor end a crossing: the sign before them is
// the one compared; a sample the window covers is marked even when unknown.
TEST(PlayCrossing, UnknownForcesAreSkippedButCovered) {
  auto t = chain0({1.0, 1.0, 0.0, -1.0, -1.0, -1.0});
  t[2] = std::nullopt;
  EXPECT_EQ(marks(play_crossing(t, 2), 0), "000110");
  // -1 at 1, unknown at 2, +1 at 3: a change at 3 against the -1 before the gap.
  t = chain0({1.0, -1.0, 1.0, 1.0, 1.0, 1.0, 1.0});
  t[2] = std::nullopt;
  EXPECT_EQ(marks(play_crossing(t, 3), 0), "0111110");
}

// No window, no marks; an empty sequence gives an empty result.
TEST(PlayCrossing, NoWindowMarksNothing) {
  const auto t = chain0({1.0, -1.0, 1.0, -1.0});
  EXPECT_EQ(marks(play_crossing(t, 0), 0), "0000");
  EXPECT_EQ(marks(play_crossing(t, -1), 0), "0000");
  EXPECT_TRUE(play_crossing({}, 5).empty());
}

}  // namespace
}  // namespace gpm::calib
