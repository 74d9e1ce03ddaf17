// Tests of models/progress.cpp: with a fake clock and a string sink (no
// sleeping, no terminal), the line shows done/total, the rate (from the
// first update on) and the ETA computed by hand, is rewritten in place at
// most once per interval, blanks
// the rest of a longer previous line, and is erased by finish(); a reporter
// without a sink (stderr not a terminal) writes nothing.
#include "models/progress.hpp"

#include <string>

#include <gtest/gtest.h>

namespace gpm {
namespace {

struct Fake {
  double now = 100.0;
  std::string out;
  int writes = 0;
  Progress make(double total, double interval = 0.25) {
    return Progress("gpm render", "frames", total,
                    [this](const std::string& s) { out += s, ++writes; }, [this] { return now; }, interval);
  }
};

TEST(Progress, LineShowsDoneTotalRateAndEta) {
  Fake f;
  const Progress p = f.make(300);
  // 120 of 300 in 2 s: 60 frames/s, 180 left -> 3.0 s.
  EXPECT_EQ(p.line(120, 2.0), "gpm render  120/300 frames  60.0 frames/s  ETA 3.0 s");
  // Past a minute: 10 of 300 in 10 s: 1 frame/s, 290 s left = 4 min 50 s.
  EXPECT_EQ(p.line(10, 10.0), "gpm render  10/300 frames  1.0 frames/s  ETA 4 min 50 s");
  // Nothing done yet: no rate, no ETA.
  EXPECT_EQ(p.line(0, 0.0), "gpm render  0/300 frames");
}

// Set-up before the first update (an OpenGL context, a video file) is not
// counted: 10 s of set-up, then 30 frames in 1 s is 30 frames/s, 60 left: 2 s.
TEST(Progress, RateCountsFromTheFirstUpdate) {
  Fake f;
  Progress p = f.make(90, 0.5);
  f.now += 10.0;
  p.update(0);
  f.now += 1.0;
  p.update(30);
  EXPECT_EQ(f.out, "\rgpm render  30/90 frames  30.0 frames/s  ETA 2.0 s");
}

TEST(Progress, UnknownTotalShowsNoEta) {
  Fake f;
  const Progress p("simulate", "s simulated", 0.0, [&f](const std::string& s) { f.out += s; },
                   [&f] { return f.now; });
  EXPECT_EQ(p.line(2.5, 5.0), "simulate  2.5 s simulated  0.5 s simulated/s");
}

TEST(Progress, RewritesInPlaceAtMostOncePerInterval) {
  Fake f;
  Progress p = f.make(100);
  p.update(0);  // starts the clock, writes nothing
  // Times in binary fractions of a second, so that the sums are exact.
  for (int k = 1; k <= 10; ++k) {  // 10 updates within 10/64 s: nothing yet
    f.now += 1.0 / 64;
    p.update(k);
  }
  EXPECT_EQ(f.writes, 0);
  f.now += 6.0 / 64;  // 0.25 s since the start
  p.update(11);
  ASSERT_EQ(f.writes, 1);
  EXPECT_EQ(f.out, "\r" + p.line(11, 0.25));
  // 1 s more of updates every 1/128 s: 4 lines (one per 0.25 s).
  for (int k = 0; k < 128; ++k) {
    f.now += 1.0 / 128;
    p.update(12 + k * 0.5);
  }
  EXPECT_EQ(f.writes, 5);
  EXPECT_EQ(f.out.back() == '\n', false) << "the line is rewritten, never scrolled";
}

TEST(Progress, ShorterLineBlanksTheRestOfTheLongerOne) {
  Fake f;
  Progress p = f.make(0, 0.0);
  p.update(0);
  f.now += 1.0;
  p.update(1000.5);  // "... 1000.5 frames  1000.5 frames/s"
  const std::string first = f.out;
  f.out.clear();
  f.now += 1000.0;
  p.update(1);  // a shorter line
  const std::string shorter = p.line(1, 1001.0);
  ASSERT_LT(shorter.size() + 1, first.size());
  EXPECT_EQ(f.out, "\r" + shorter + std::string(first.size() - 1 - shorter.size(), ' '));
}

TEST(Progress, FinishErasesTheLineAndSilencesLaterUpdates) {
  Fake f;
  Progress p = f.make(10, 0.0);
  p.update(0);
  f.now += 1.0;
  p.update(5);
  const size_t n = f.out.size() - 1;  // the line without its \r
  f.out.clear();
  p.finish();
  EXPECT_EQ(f.out, "\r" + std::string(n, ' ') + "\r");
  f.out.clear();
  f.now += 1.0;
  p.update(6);
  p.finish();
  EXPECT_EQ(f.out, "");
}

TEST(Progress, NothingWrittenBeforeAnyLineOrWithoutASink) {
  Fake f;
  { Progress p = f.make(10); }  // destroyed without an update: nothing to erase
  EXPECT_EQ(f.out, "");
  Progress silent("x", "frames", 10, nullptr, [&f] { return f.now; }, 0.0);
  EXPECT_FALSE(silent.active());
  f.now += 1.0;
  silent.update(3);  // no sink: nothing happens, nothing crashes
  silent.finish();
  Progress quiet = Progress::silent();
  EXPECT_FALSE(quiet.active());
  quiet.update(1);
}

TEST(Progress, DestructorErasesAnUnfinishedLine) {
  Fake f;
  {
    Progress p = f.make(10, 0.0);
    p.update(0);
    f.now += 1.0;
    p.update(2);
  }
  EXPECT_EQ(f.out.back(), '\r');
  EXPECT_EQ(f.writes, 2);
}

}  // namespace
}  // namespace gpm
