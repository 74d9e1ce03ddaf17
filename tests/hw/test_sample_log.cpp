// Tests of hw/procedures/sample_log.cpp: appended rows are on disk at once, existing
// files are never overwritten, resume keeps rows and drops a torn last line and
// refuses an id twice; a device or FIFO is written in place or refused at
// once; a log in memory records its rows and writes nothing.
#include <gtest/gtest.h>

#include <filesystem>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "hw/hw_errors.hpp"
#include "hw/procedures/sample_log.hpp"
#include "hw_test_util.hpp"
#include "models/bounds.hpp"
#include "models/errors.hpp"
#include "models/samples.hpp"

namespace gpm::hw {
namespace {

TEST(SampleLog, ALogInMemoryRecordsItsRowsAndWritesNothing) {
  SampleLog log(SampleColumns::kOnTheFly);
  SampleMotion m;
  m.t_s = 0.25;
  m.tau = Eigen::Vector3d(0.1, -0.2, 0.3);
  log.append(0, Eigen::Vector3d(1.0, 2.0, 3.0), Eigen::Vector2d(216.5, 250.0), m);
  log.append(1, Eigen::Vector3d(1.5, 2.5, 3.5), Eigen::Vector2d(217.0, 250.0), m);
  log.sync();
  EXPECT_EQ(log.size(), 2u);
  EXPECT_TRUE(log.has(1));
  const SampleLog::Recorded& r = log.recorded().at(1);
  EXPECT_EQ(r.theta_m, Eigen::Vector3d(1.5, 2.5, 3.5));
  ASSERT_TRUE(r.motion);
  EXPECT_EQ(r.motion->tau, m.tau);
  EXPECT_FALSE(std::filesystem::exists(log.path()));  // a name for messages, not a file
  EXPECT_THROW(log.append(2, Eigen::Vector3d::Zero(), Eigen::Vector2d::Zero()), HardwareError);  // columns kept
}

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
  // recorded(): the rows found (none) and those appended since, as written.
  ASSERT_EQ(log.recorded().size(), 1u);
  EXPECT_EQ(log.recorded().at(0).theta_m, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(log.recorded().at(0).target, Eigen::Vector2d(4, 5));
}

TEST(SampleLog, ResumeRefusesAnIdTwice) {
  const test::TempDir dir("log_dup");
  const auto path = (dir / "s.csv").string();
  const std::string text = "sample,theta_m1,theta_m2,theta_m3,target_x,target_y\n0,1,2,3,4,5\n1,1,2,3,4,5\n0,1,2,3,4,5\n";
  test::write_text(path, text);
  try {
    SampleLog log(path, true);
    ADD_FAILURE() << "an id twice was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("sample 0 appears twice"), std::string::npos) << e.what();
  }
  EXPECT_EQ(test::read_text(path), text);
}

std::string error_of(const std::string& path, bool resume) {
  try {
    SampleLog log(path, resume);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// A file that is not a sampling log (first line other than the log's header)
// is left byte for byte as it is, with or without --resume (the torn-line
// rule once truncated such a file: "notes" without a newline became empty,
// the last line of "a,b\nc" was dropped before the header was checked).
TEST(SampleLog, AnotherFileIsLeftAsItIs) {
  const test::TempDir dir("log_other");
  const auto path = (dir / "s.csv").string();
  for (const std::string& text : {std::string("notes without a newline"), std::string("a,b\nc"),
                                 std::string("sample,theta_m1,theta_m2,theta_m3,x,y\n0,1,2,3,4,5\n1,1,2")}) {
    for (const bool resume : {false, true}) {
      test::write_text(path, text);
      EXPECT_NE(error_of(path, resume).find("is not a samples log"), std::string::npos) << text;
      EXPECT_EQ(test::read_text(path), text);
    }
  }
  // A header begun (a session stopped while writing it) holds nothing: started again.
  test::write_text(path, "sample,theta_m1,th");
  { SampleLog log(path, false); }
  EXPECT_EQ(test::read_text(path), "sample,theta_m1,theta_m2,theta_m3,target_x,target_y\n");
}

// A log that cannot be created (missing folder; a read-only or full one
// alike) is refused when it is opened, before a session moves anything (the
// file used to be created by the first sample, after the first motion).
TEST(SampleLog, AFileThatCannotBeCreatedIsRefusedAtOnce) {
  const test::TempDir dir("log_missing");
  const auto path = (dir / "no_such_folder" / "s.csv").string();
  EXPECT_NE(error_of(path, false).find("no_such_folder/s.csv: cannot create: No such file or directory"),
            std::string::npos);
  const auto made = (dir / "s.csv").string();
  {
    SampleLog log(made, false);
    EXPECT_EQ(test::read_text(made), "sample,theta_m1,theta_m2,theta_m3,target_x,target_y\n");  // made at once
  }
  EXPECT_FALSE(std::filesystem::exists(made));  // and removed: nothing was recorded
}

// A resumed log is read with the bound of every samples reader (64 MiB,
// models/bounds.hpp): a larger one is refused and left as it is.
TEST(SampleLog, ResumeIsBoundedLikeEverySamplesReader) {
  const test::TempDir dir("log_big");
  const auto path = (dir / "s.csv").string();
  test::write_text(path, "sample,theta_m1,theta_m2,theta_m3,target_x,target_y\n0,1,2,3,4,5\n");
  const auto size = static_cast<off_t>(limits::kMaxCsvBytes) + 1;
  ASSERT_EQ(::truncate(path.c_str(), size), 0);  // sparse: no 64 MiB written
  EXPECT_NE(error_of(path, true).find("larger than 64 MiB"), std::string::npos);
  EXPECT_EQ(std::filesystem::file_size(path), static_cast<std::uintmax_t>(size));
}

// A device or FIFO: the header is written at once (a refusal, InputError,
// comes before any session moves), samples in place, never fsynced, read
// back, locked or resumed.
TEST(SampleLog, DeviceOrFifoIsWrittenInPlaceOrRefusedAtOnce) {
  {
    SampleLog log("/dev/null", false);
    EXPECT_NO_THROW(log.append(0, {1.0, 3.0, 4.5}, {216.5, 250}));
    SampleLog second("/dev/null", false);  // not locked
    log.close_and_discard_if_empty();
  }
  EXPECT_THROW(SampleLog("/dev/null", true), InputError);  // nothing to resume
  EXPECT_THROW(SampleLog("/dev/full", false), InputError);  // the header cannot be written
  const test::TempDir dir("log_fifo");
  const auto fifo = (dir / "fifo").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  try {
    SampleLog log(fifo, false);
    ADD_FAILURE() << "a FIFO nobody reads was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no process reads this FIFO"), std::string::npos) << e.what();
  }
  const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
  ASSERT_GE(reader, 0);
  {
    SampleLog log(fifo, false);
    log.append(7, {1.0, 3.0, 4.5}, {216.5, 250});
  }
  char buf[256] = {};
  const ssize_t n = ::read(reader, buf, sizeof buf - 1);
  ::close(reader);
  ASSERT_GT(n, 0);
  EXPECT_EQ(std::string(buf), "sample,theta_m1,theta_m2,theta_m3,target_x,target_y\n7,1,3,4.5,216.5,250\n");
  EXPECT_TRUE(std::filesystem::is_fifo(fifo));
  EXPECT_THROW(SampleLog(dir.path().string(), false), InputError);  // a folder
}

}  // namespace
}  // namespace gpm::hw
