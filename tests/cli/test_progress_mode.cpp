// Tests of app/progress_mode.cpp: the --progress modes, timed by a fake clock.
#include "app/progress_mode.hpp"

#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace gpm::cli {
namespace {

// A reporter writing into lines, timed by now.
struct Fixture {
  double now = 100.0;
  std::vector<std::string> written;
  StatusReporter reporter(ProgressMode mode) {
    return StatusReporter("gpm run", mode, [this](const std::string& s) { written.push_back(s); },
                          [this] { return now; });
  }
};

TEST(ProgressMode, DefaultIsBarOnATerminalAndLineOtherwise) {
  EXPECT_EQ(progress_mode("", true), ProgressMode::kBar);
  EXPECT_EQ(progress_mode("", false), ProgressMode::kLine);
  EXPECT_EQ(progress_mode("none", true), ProgressMode::kNone);
  EXPECT_EQ(progress_mode("line", true), ProgressMode::kLine);
  EXPECT_EQ(progress_mode("bar", false), ProgressMode::kBar);
}

TEST(StatusReporter, LineModeWritesOneLinePerIntervalNotPerUpdate) {
  Fixture f;
  auto r = f.reporter(ProgressMode::kLine);
  // 21 s of updates every 0.5 s: a line at 5, 10, 15 and 20 s after the start.
  for (int k = 0; k <= 42; ++k) {
    f.now = 100.0 + 0.5 * k;
    r.update(k < 20 ? "simulating" : "calibrating");
  }
  ASSERT_EQ(f.written.size(), 4u);
  EXPECT_EQ(f.written[0], "gpm run: simulating, 5 s\n");
  EXPECT_EQ(f.written[3], "gpm run: calibrating, 20 s\n");
  for (const std::string& line : f.written) EXPECT_EQ(line.find('\r'), std::string::npos);
}

TEST(StatusReporter, LineModeTicksDuringALongStage) {
  Fixture f;
  auto r = f.reporter(ProgressMode::kLine);
  r.update("simulating");  // at the start: no line yet
  EXPECT_TRUE(f.written.empty());
  for (int s = 1; s <= 30; ++s) {  // one stage of 30 s, no update: the heartbeat's ticks
    f.now = 100.0 + s;
    r.tick();
  }
  ASSERT_EQ(f.written.size(), 6u);
  EXPECT_EQ(f.written[5], "gpm run: simulating, 30 s\n");
  r.finish();
  f.now += 10.0;
  r.tick();
  EXPECT_EQ(f.written.size(), 6u);  // nothing after finish
}

TEST(StatusReporter, BarModeRewritesOneLineAndClearsIt) {
  Fixture f;
  auto r = f.reporter(ProgressMode::kBar);
  r.update("simulating");
  r.update("simulating");  // unchanged: not rewritten
  r.update("fit");
  r.finish();
  ASSERT_EQ(f.written.size(), 3u);
  EXPECT_EQ(f.written[0], "\rgpm run: simulating");
  EXPECT_EQ(f.written[1], "\rgpm run: fit" + std::string(7, ' '));  // blanks the longer line's rest
  EXPECT_EQ(f.written[2], "\r" + std::string(12, ' ') + "\r");  // the shown line is 12 characters + blanks
}

TEST(StatusReporter, NoneWritesNothing) {
  Fixture f;
  auto r = f.reporter(ProgressMode::kNone);
  for (int k = 0; k < 100; ++k) {
    f.now += 1.0;
    r.update("simulating");
    r.tick();
  }
  r.finish();
  EXPECT_TRUE(f.written.empty());
}

TEST(CountingProgress, NoneIsSilent) { EXPECT_FALSE(counting_progress(ProgressMode::kNone, "gpm simulate", "s").active()); }

}  // namespace
}  // namespace gpm::cli
