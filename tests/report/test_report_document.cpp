// Tests of report/report_document.cpp: the same content in Markdown and
// self-contained HTML.
#include "report/report_document.hpp"

#include <filesystem>
#include <fstream>
#include <iterator>

#include <unistd.h>

#include <gtest/gtest.h>

#include "models/output_file.hpp"

namespace gpm::report {
namespace {

TEST(ReportDocument, MarkdownAndHtmlCarryTheSameContent) {
  ReportDocument d;
  d.heading(1, "Calibration <report>");
  d.paragraph("Before & after.");
  d.table({"param", "value"}, {{"la1", "244.1"}, {"dth1", "0.01"}});
  d.figure("layout", "Sample layout", "<svg><circle/></svg>");
  d.bullets({"one", "two"});
  const std::string md = d.markdown();
  EXPECT_NE(md.find("# Calibration <report>"), std::string::npos);
  EXPECT_NE(md.find("| param | value |\n| --- | --- |\n| la1 | 244.1 |"), std::string::npos);
  EXPECT_NE(md.find("![Sample layout](layout.svg)"), std::string::npos);
  EXPECT_NE(md.find("- two\n"), std::string::npos);
  const std::string html = d.html("t");
  EXPECT_NE(html.find("<h1>Calibration &lt;report&gt;</h1>"), std::string::npos);
  EXPECT_NE(html.find("<td>la1</td><td>244.1</td>"), std::string::npos);
  EXPECT_NE(html.find("<svg><circle/></svg>"), std::string::npos);  // inline, self-contained
  EXPECT_EQ(html.find("layout.svg"), std::string::npos);
  ASSERT_EQ(d.figure_files().size(), 1u);
  EXPECT_EQ(d.figure_files()[0].first, "layout.svg");
}

TEST(ReportDocument, StagedFilesAppearOnlyAtCommit) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("gpm_report_document_test_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  ReportDocument d;
  d.heading(1, "Staged");
  d.figure("plot", "A plot", "<svg/>");
  {
    OutputFolder out(dir.string());
    d.stage(out, "report", "Staged");
    EXPECT_FALSE(fs::exists(dir / "report.md"));  // nothing in place before commit
    out.commit();
  }
  std::ifstream md(dir / "report.md");
  const std::string text((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, d.markdown());
  EXPECT_TRUE(fs::exists(dir / "report.html"));
  EXPECT_TRUE(fs::exists(dir / "plot.svg"));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 3);
  fs::remove_all(dir);
  {
    OutputFolder out(dir.string());
    d.stage(out, "report", "Staged");
  }  // not committed: nothing, not even the folder
  EXPECT_FALSE(fs::exists(dir));
}

}  // namespace
}  // namespace gpm::report
