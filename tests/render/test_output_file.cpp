// Tests of render/output_file.cpp: all-or-nothing output files.
#include <fstream>

#include <gtest/gtest.h>

#include "models/errors.hpp"
#include "render/output_file.hpp"
#include "render_test_util.hpp"

namespace gpm::render {
namespace {

namespace fs = std::filesystem;

TEST(OutputFile, TemporaryNameIsHiddenInTheSameFolder) {
  const fs::path tmp = temporary_name_for("/some/folder/video.mp4");
  EXPECT_EQ(tmp.parent_path(), fs::path("/some/folder"));
  EXPECT_EQ(tmp.filename().string().rfind(".video.mp4.tmp", 0), 0u);
}

TEST(OutputFile, WritableFolderPassesAndLeavesNothing) {
  const fs::path d = testing::fresh_dir("writable");
  EXPECT_NO_THROW(check_output_file((d / "a.mp4").string()));
  EXPECT_TRUE(fs::is_empty(d));
  fs::remove_all(d);
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
  const fs::path d = testing::fresh_dir("folder");
  EXPECT_THROW(check_output_file(d.string()), InputError);
  // /proc refuses new files even for root.
  EXPECT_THROW(check_output_file("/proc/gpm-render-test.mp4"), InputError);
  fs::remove_all(d);
}

TEST(OutputFile, CommitRenamesIntoPlace) {
  const fs::path d = testing::fresh_dir("commit");
  const std::string dst = (d / "out.txt").string();
  const std::string tmp = temporary_name_for(dst);
  std::ofstream(tmp) << "hello";
  commit_output_file(tmp, dst);
  EXPECT_FALSE(fs::exists(tmp));
  std::ifstream in(dst);
  std::string text;
  in >> text;
  EXPECT_EQ(text, "hello");
  fs::remove_all(d);
}

}  // namespace
}  // namespace gpm::render
