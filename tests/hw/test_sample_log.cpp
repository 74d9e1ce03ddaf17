// Tests of hw/sample_log.cpp: appended rows are on disk at once, existing
// files are never overwritten, resume keeps rows and drops a torn last line.
#include <gtest/gtest.h>

#include "hw/sample_log.hpp"
#include "hw_test_util.hpp"
#include "models/errors.hpp"
#include "models/samples.hpp"

namespace gpm::hw {
namespace {

TEST(SampleLog, AppendsAndFlushesEachSample) {
  const auto dir = test::temp_dir("log");
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
  const auto dir = test::temp_dir("log2");
  const auto path = (dir / "s.csv").string();
  test::write_text(path, "sample,theta_m1,theta_m2,theta_m3\n0,1,2,3\n");
  EXPECT_THROW(SampleLog(path, false), InputError);
  EXPECT_EQ(test::read_text(path), "sample,theta_m1,theta_m2,theta_m3\n0,1,2,3\n");
}

TEST(SampleLog, ResumeDropsATornLine) {
  const auto dir = test::temp_dir("log3");
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
  const auto dir = test::temp_dir("log4");
  const auto path = dir / "s.csv";
  SampleLog log(path.string(), false);
  log.close_and_discard_if_empty();
  EXPECT_FALSE(std::filesystem::exists(path));
}

}  // namespace
}  // namespace gpm::hw
