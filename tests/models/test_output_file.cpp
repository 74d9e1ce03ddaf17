// Tests of models/output_file.cpp: the output policy (staged regular files,
// devices and FIFOs written in place, symlinks followed, an input never
// overwritten, temporaries removed on errors and on signals, folders all or
// nothing).
#include "models/output_file.hpp"

#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "models/errors.hpp"
#include "temp_files.hpp"

namespace gpm {
namespace {

namespace fs = std::filesystem;

using test::put;
using test::slurp;
using test::TempDir;

TEST(OutputFile, TemporaryNameIsHiddenInTheSameFolder) {
  const fs::path tmp = temporary_name_for("/some/folder/video.mp4");
  EXPECT_EQ(tmp.parent_path(), fs::path("/some/folder"));
  EXPECT_EQ(tmp.filename().string().rfind(".video.mp4.tmp", 0), 0u);
}

TEST(OutputFile, WritableFolderPassesAndLeavesNothing) {
  const TempDir d("writable");
  EXPECT_NO_THROW(check_output_file(d / "a.mp4"));
  EXPECT_TRUE(fs::is_empty(d.path));
}

TEST(OutputFile, MissingFolderIsOneClearLine) {
  try {
    check_output_file("/nonexistent-gpm-folder/x.mp4");
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("/nonexistent-gpm-folder/x.mp4: cannot write: folder"), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos);
  }
}

TEST(OutputFile, FolderAsFileAndUncreatableFileAreErrors) {
  const TempDir d("folder");
  EXPECT_THROW(check_output_file(d.path.string()), InputError);
  // /proc refuses new files even for root.
  EXPECT_THROW(check_output_file("/proc/gpm-render-test.mp4"), InputError);
}

TEST(OutputFile, CommitRenamesIntoPlace) {
  const TempDir d("commit");
  const std::string dst = d / "out.txt";
  const std::string tmp = temporary_name_for(dst);
  put(tmp, "hello");
  commit_output_file(tmp, dst);
  EXPECT_FALSE(fs::exists(tmp));
  EXPECT_EQ(slurp(dst), "hello");
}

TEST(OutputFile, RegularFileIsReplacedWholeAndKeepsItsPermissions) {
  const TempDir d("regular");
  const std::string f = d / "r.yaml";
  put(f, "old text that is longer than the new one\n");
  ::chmod(f.c_str(), 0600);
  write_output_file(f, "new\n");
  EXPECT_EQ(slurp(f), "new\n");
  struct stat st {};
  ASSERT_EQ(::stat(f.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600u);
  EXPECT_EQ(std::distance(fs::directory_iterator(d.path), fs::directory_iterator()), 1);
}

TEST(OutputFile, DeviceIsWrittenInPlaceNeverReplaced) {
  // Before the policy, a rename over /dev/null made it a regular file (as root).
  write_output_file("/dev/null", "discarded\n");
  struct stat st {};
  ASSERT_EQ(::stat("/dev/null", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
  OutputFile out("/dev/null");
  EXPECT_TRUE(out.in_place());
  EXPECT_EQ(out.write_path(), "/dev/null");
  out.discard();  // never removes the device
  ASSERT_EQ(::stat("/dev/null", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
}

TEST(OutputFile, FifoIsWrittenInPlace) {
  const TempDir d("fifo");
  const std::string f = d / "pipe";
  ASSERT_EQ(::mkfifo(f.c_str(), 0600), 0);
  const int reader = ::open(f.c_str(), O_RDONLY | O_NONBLOCK);  // so that the writer's open returns
  ASSERT_GE(reader, 0);
  write_output_file(f, "through the pipe");
  char buf[64] = {};
  const ssize_t n = ::read(reader, buf, sizeof buf - 1);
  ::close(reader);
  EXPECT_EQ(std::string(buf, n > 0 ? static_cast<size_t>(n) : 0u), "through the pipe");
  struct stat st {};
  ASSERT_EQ(::lstat(f.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
}

TEST(OutputFile, SymlinkIsFollowedNotReplaced) {
  const TempDir d("link");
  fs::create_directories(d.path / "sub");
  const std::string real = d / "sub/real.yaml";
  put(real, "old");
  fs::create_symlink("sub/real.yaml", d.path / "link.yaml");  // relative to the link's folder
  write_output_file(d / "link.yaml", "new");
  EXPECT_TRUE(fs::is_symlink(d.path / "link.yaml"));
  EXPECT_EQ(slurp(real), "new");
  // A dangling link: its target is created.
  fs::create_symlink("sub/made.yaml", d.path / "dangling.yaml");
  write_output_file(d / "dangling.yaml", "made");
  EXPECT_TRUE(fs::is_symlink(d.path / "dangling.yaml"));
  EXPECT_EQ(slurp(d / "sub/made.yaml"), "made");
  EXPECT_TRUE(fs::is_empty(d.path / "sub") == false);
  EXPECT_EQ(std::distance(fs::directory_iterator(d.path / "sub"), fs::directory_iterator()), 2);
}

TEST(OutputFile, OutputThatIsAnInputIsRefused) {
  const TempDir d("input");
  const std::string s = d / "s.csv";
  put(s, "measurements");
  fs::create_symlink(s, d.path / "alias.csv");
  for (const std::string& out : {s, d / "alias.csv", d / "./s.csv"}) {
    try {
      write_output_file(out, "result", {d / "other.csv", s});
      FAIL() << out << ": not refused";
    } catch (const InputError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("is also an input"), std::string::npos) << m;
      EXPECT_EQ(m.find('\n'), std::string::npos);
    }
    EXPECT_EQ(slurp(s), "measurements");
  }
  // A different file of the same name elsewhere is not an input.
  EXPECT_NO_THROW(write_output_file(d / "r.csv", "result", {s}));
}

TEST(OutputFile, UncommittedTemporaryIsRemoved) {
  const TempDir d("uncommitted");
  try {
    OutputFile out(d / "x.txt");
    put(out.write_path(), "half");
    throw std::runtime_error("failure while writing");
  } catch (const std::runtime_error&) {
  }
  EXPECT_TRUE(fs::is_empty(d.path));
}

TEST(OutputFile, SignalRemovesTheTemporariesAndExits130) {
  const TempDir d("signal");
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    install_output_signal_cleanup();
    OutputFile out(d / "video.mp4");
    put(out.write_path(), "partial");
    OutputFolder folder(d / "run");
    folder.add("report.md", "partial");
    ::raise(SIGINT);
    ::_exit(0);  // not reached
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130);
  EXPECT_TRUE(fs::is_empty(d.path)) << "left: " << fs::directory_iterator(d.path)->path();
}

TEST(OutputFolder, CommitsAllFilesAndKeepsOthers) {
  const TempDir d("folder_commit");
  put(d / "keep.txt", "kept");
  put(d / "a.csv", "old");
  {
    OutputFolder out(d.path.string());
    out.add("a.csv", "A");
    out.add("b.md", "B");
    out.commit();
  }
  EXPECT_EQ(slurp(d / "a.csv"), "A");
  EXPECT_EQ(slurp(d / "b.md"), "B");
  EXPECT_EQ(slurp(d / "keep.txt"), "kept");
  EXPECT_EQ(std::distance(fs::directory_iterator(d.path), fs::directory_iterator()), 3);
}

TEST(OutputFolder, NothingWhenNotCommittedOrRefused) {
  const TempDir d("folder_none");
  {
    OutputFolder out(d / "new");
    out.add("a.csv", "A");
  }  // not committed: the folder made here is removed again
  EXPECT_TRUE(fs::is_empty(d.path));
  put(d / "in.yaml", "input");
  {
    OutputFolder out(d.path.string(), {d / "in.yaml"});
    out.add("a.csv", "A");
    out.add("in.yaml", "would overwrite the input");
    EXPECT_THROW(out.commit(), InputError);
  }
  EXPECT_EQ(slurp(d / "in.yaml"), "input");
  EXPECT_FALSE(fs::exists(d / "a.csv"));  // refused before anything moved
  EXPECT_EQ(std::distance(fs::directory_iterator(d.path), fs::directory_iterator()), 1);
  put(d / "file", "x");
  EXPECT_THROW(OutputFolder(d / "file"), InputError);
}

// What a command keeps when it cannot write all its files: only the kept
// names are moved in, the others stay as they were, no staging folder is left.
TEST(OutputFolder, KeepOnlyCommitsTheKeptFilesAlone) {
  const TempDir d("folder_keep_only");
  put(d / "report.md", "old report");
  {
    OutputFolder out(d.path.string());
    out.add("alarms.csv", "A");
    out.add("estimates.csv", "E");
    out.add("report.md", "new report");
    out.keep_only({"alarms.csv", "estimates.csv", "not_staged.csv"});
    out.commit();
  }
  EXPECT_EQ(slurp(d / "alarms.csv"), "A");
  EXPECT_EQ(slurp(d / "estimates.csv"), "E");
  EXPECT_EQ(slurp(d / "report.md"), "old report");
  EXPECT_FALSE(fs::exists(d / "not_staged.csv"));
  EXPECT_EQ(std::distance(fs::directory_iterator(d.path), fs::directory_iterator()), 3);
}

// Every input against every output of one command, by identity, whichever
// comes first (the command line turns tracking on; off, nothing is kept).
TEST(CommandFiles, AnOutputThatIsAnInputIsRefusedInEitherOrder) {
  const TempDir d("command_files");
  put(d / "robot.yaml", "robot");
  put(d / "summary.json", "summary");
  fs::create_symlink(d.path / "robot.yaml", d.path / "alias.yaml");
  track_command_files(true);
  // Declared first (a command's output folder), read later (a file a scenario names).
  declare_output(d / "summary.json");
  declare_output(d / "missing.csv");  // not there yet: nothing to compare
  try {
    note_input(d / "summary.json");
    ADD_FAILURE() << "not refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("summary.json: is also an input of this command"), std::string::npos)
        << e.what();
  }
  // Read first, declared later: a link to the input is the same file.
  note_input(d / "robot.yaml");
  EXPECT_THROW(declare_output(d / "alias.yaml"), InputError);
  EXPECT_NO_THROW(declare_output(d / "other.yaml"));
  EXPECT_NO_THROW(note_input("/dev/null"));  // devices and FIFOs are written in place, never replaced
  EXPECT_NO_THROW(declare_output("/dev/null"));
  // OutputFile and OutputFolder declare their files.
  EXPECT_THROW(write_output_file(d / "robot.yaml", "replaced"), InputError);
  {
    OutputFolder out(d.path.string());
    EXPECT_THROW(out.add("alias.yaml", "replaced"), InputError);
  }
  EXPECT_EQ(slurp(d / "robot.yaml"), "robot");
  track_command_files(false);  // off: nothing kept, nothing refused
  EXPECT_NO_THROW(note_input(d / "summary.json"));
  EXPECT_NO_THROW(declare_output(d / "robot.yaml"));
}

}  // namespace
}  // namespace gpm
