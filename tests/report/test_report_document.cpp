// Tests of report/report_document.cpp: the same content in Markdown and
// self-contained HTML; valid GFM tables, code spans, no Markdown in HTML.
#include "report/report_document.hpp"

#include <filesystem>
#include <fstream>
#include <iterator>

#include <unistd.h>

#include <gtest/gtest.h>

#include "models/output_file.hpp"
#include "report_text_checks.hpp"

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
  EXPECT_NE(html.find("<div class=\"scroll\"><table><tr>"), std::string::npos);  // scrolls in its own box
  EXPECT_NE(html.find("<td>la1</td><td>244.1</td>"), std::string::npos);
  EXPECT_NE(html.find("<svg><circle/></svg>"), std::string::npos);  // inline, self-contained
  EXPECT_EQ(html.find("layout.svg"), std::string::npos);
  ASSERT_EQ(d.figure_files().size(), 1u);
  EXPECT_EQ(d.figure_files()[0].first, "layout.svg");
}

TEST(ReportDocument, PipesInCellsAreEscapedSoEveryRowKeepsItsCellCount) {
  ReportDocument d;
  d.table({"parameter", "|error| / CRB σ"}, {{"la1", "a | b"}, {"la2"}});
  const std::string md = d.markdown();
  EXPECT_NE(md.find("| parameter | \\|error\\| / CRB σ |\n| --- | --- |\n| la1 | a \\| b |\n| la2 |  |\n"),
            std::string::npos)
      << md;
  int tables = 0;
  EXPECT_TRUE(testing::markdown_table_errors(md, &tables).empty());
  EXPECT_EQ(tables, 1);
  // HTML has no escapes: the header reads as written.
  EXPECT_NE(d.html("t").find(">|error| / CRB σ</th>"), std::string::npos);
}

TEST(ReportDocument, CodeSpansBecomeCodeInHtmlAndStayInMarkdown) {
  ReportDocument d;
  d.lead("Before 9.7 mm, after 9.3 µm.");
  d.paragraph("The `actual` row & `a<b>`; an unpaired ` stays.");
  d.bullets({"run `gpm run`"});
  d.heading(1, "gpm monitor: monitor_offset_jump_realistic");
  const std::string md = d.markdown(), html = d.html("t");
  EXPECT_NE(md.find("**Before 9.7 mm, after 9.3 µm.**\n"), std::string::npos);
  EXPECT_NE(md.find("The `actual` row & `a<b>`; an unpaired ` stays."), std::string::npos);
  EXPECT_NE(html.find("<p class=\"lead\">Before 9.7 mm, after 9.3 µm.</p>"), std::string::npos);
  EXPECT_NE(html.find("<p>The <code>actual</code> row &amp; <code>a&lt;b&gt;</code>; an unpaired ` stays.</p>"),
            std::string::npos)
      << html;
  EXPECT_NE(html.find("<li>run <code>gpm run</code></li>"), std::string::npos);
  // A long name splits after its underscores, not inside a word.
  EXPECT_NE(html.find("<h1>gpm monitor: monitor_<wbr>offset_<wbr>jump_<wbr>realistic</h1>"), std::string::npos);
}

TEST(ReportDocument, TheChecksOfTablesAndLeakedMarkdownCanFail) {
  // A header with bare pipes (the old parameter table) and a short row.
  const std::string md = "| a | |error| |\n| --- | --- |\n| 1 | 2 |\n\n| x | y |\n| --- | --- |\n| 1 |\n";
  int tables = 0;
  const auto errors = testing::markdown_table_errors(md, &tables);
  EXPECT_EQ(tables, 2);
  ASSERT_EQ(errors.size(), 3u);  // the header against its rule, its row, the short row
  EXPECT_NE(errors[0].find("header of 4 cells, delimiter row of 2"), std::string::npos) << errors[0];
  const auto leaks = testing::leaked_markdown(
      "<p>The `actual` row: x1.05e+03, 9.3 um, **bold**</p><svg><text>1e-05</text><svg>in</svg>2e-07</svg>"
      "<pre>`kept`</pre>");
  ASSERT_EQ(leaks.size(), 4u);
  EXPECT_EQ(leaks[0].rfind("backtick", 0), 0u);
  EXPECT_EQ(leaks[1].rfind("emphasis", 0), 0u);
  EXPECT_EQ(leaks[2].rfind("C exponent", 0), 0u);
  EXPECT_EQ(leaks[3].rfind("ASCII unit", 0), 0u);
  EXPECT_TRUE(testing::leaked_markdown("<p>ok 1.05×10³ µm</p><svg><svg>1e-05</svg><text>2e-07</text></svg>").empty());
}

// ASCII units of terminal text as symbols, only where they are units: after
// a number (um, urad), or the word chi2; names and other words stay.
TEST(ReportDocument, UnitSymbolsReplaceOnlyUnits) {
  EXPECT_EQ(unit_symbols("RMS 28.15 um, 3um, 12 urad"), "RMS 28.15 µm, 3µm, 12 µrad");
  EXPECT_EQ(unit_symbols("the smallest chi2/dof of the speeds tried (0.1: 1.03)"),
            "the smallest χ²/dof of the speeds tried (0.1: 1.03)");
  EXPECT_EQ(unit_symbols("chi2 threshold 12.3; chi2 2866"), "χ² threshold 12.3; χ² 2866");
  EXPECT_EQ(unit_symbols("model_test_chi2 and chi2x, umbrella, drum 5 umbrellas"),
            "model_test_chi2 and chi2x, umbrella, drum 5 umbrellas");
  EXPECT_EQ(readable_text("model test passes (chi2/dof 1.03, p 0.122): 1.5e-05 rad"),
            "model test passes (χ²/dof 1.03, p 0.122): 1.5×10⁻⁵ rad");
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
