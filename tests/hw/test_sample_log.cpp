// Tests of hw/procedures/sample_log.cpp: appended rows are on disk at once, existing
// files are never overwritten, resume keeps rows and drops a torn last line.
#include <gtest/gtest.h>

#include "hw/procedures/sample_log.hpp"
#include "hw_test_util.hpp"
#include "models/errors.hpp"
#include "models/samples.hpp"

namespace gpm::hw {
namespace {

TEST(SampleLog, AppendsAndFlushesEachSample) {
  const test::TempDir dir("log");
  const auto path = (dir / "s.csv").string();
  SampleLog log(path, false);
  log.append(0, {1.0, 3.0, 4.5}, {216.5, 250});
  // Readable by another reader while the log is still open.
  Samples s = read_samples_csv(path);
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s.theta_m[0][2], 4.5);
  log.append(1, {1.25, 3.0, 4.5}, {216.5, 250});
  EXPECT_EQ(read_samples_csv(path).size(), 2u);
  EXPECT_TRUE(log.has(1));
  EXPECT_FALSE(log.has(2));
}

TEST(SampleLog, RefusesToOverwriteWithoutResume) {
  const test::TempDir dir("log2");
  const auto path = (dir / "s.csv").string();
  test::write_text(path, "sample,theta_m1,theta_m2,theta_m3\n0,1,2,3\n");
  EXPECT_THROW(SampleLog(path, false), InputError);
  EXPECT_EQ(test::read_text(path), "sample,theta_m1,theta_m2,theta_m3\n0,1,2,3\n");
}

TEST(SampleLog, ResumeDropsATornLine) {
  const test::TempDir dir("log3");
  const auto path = (dir / "s.csv").string();
  test::write_text(path, "sample,theta_m1,theta_m2,theta_m3,target_x,target_y\n0,1,2,3,4,5\n3,1,2,3,4,5\n4,1.1,2");
  SampleLog log(path, true);
  EXPECT_EQ(log.size(), 2u);
  EXPECT_TRUE(log.has(3));
  EXPECT_FALSE(log.has(4));
  log.append(4, {1, 2, 3}, {4, 5});
  const Samples s = read_samples_csv(path);
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s.id[2], 4);
}

TEST(SampleLog, EmptyNewLogIsRemoved) {
  const test::TempDir dir("log4");
  const auto path = dir / "s.csv";
  SampleLog log(path.string(), false);
  log.close_and_discard_if_empty();
  EXPECT_FALSE(std::filesystem::exists(path));
}

// Two sessions on one file cannot both append (two concurrent resumes once
// wrote duplicate ids): the second is refused while the first holds it.
TEST(SampleLog, ASecondLogOnTheSameFileIsRefused) {
  const test::TempDir dir("log5");
  const auto path = (dir / "s.csv").string();
  SampleLog first(path, false);
  first.append(0, {1, 2, 3}, {4, 5});
  try {
    SampleLog second(path, true);
    FAIL() << "a second log opened a locked file";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("another session is appending"), std::string::npos) << e.what();
  }
  first.close_and_discard_if_empty();
  SampleLog third(path, true);  // free again once the first is closed
  EXPECT_TRUE(third.has(0));
}

// A log that records nothing leaves no file, so a run refused before its
// first sample does not block the next one; a header-only file holds no
// measurement and is started again without --resume.
TEST(SampleLog, NothingRecordedLeavesNoFileAndHeaderOnlyFilesAreReused) {
  const test::TempDir dir("log6");
  const auto path = dir / "s.csv";
  { SampleLog log(path.string(), false); }
  EXPECT_FALSE(std::filesystem::exists(path));
  test::write_text(path, "sample,theta_m1,theta_m2,theta_m3,target_x,target_y\n");
  SampleLog log(path.string(), false);
  log.append(0, {1, 2, 3}, {4, 5});
  EXPECT_EQ(read_samples_csv(path.string()).size(), 1u);
  EXPECT_EQ(log.recorded().size(), 0u);
}

}  // namespace
}  // namespace gpm::hw
