// A report built once and written twice: Markdown (figures as SVG files
// beside it) and a self-contained HTML page (figures inline), staged in an
// output folder that commits all files or none. Text may mark code or file
// names with backticks (`gpm run`): Markdown keeps them, HTML sets them as
// <code>; no other Markdown syntax reaches the HTML page, and its text
// shows C exponents as powers of ten and ASCII units with their symbols.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace gpm {
class OutputFolder;
}

namespace gpm::report {

class ReportDocument {
 public:
  // Adds a heading of level 1..3.
  void heading(int level, const std::string& text);
  // Adds a paragraph of plain text.
  void paragraph(const std::string& text);
  // Adds the lead: the one paragraph a reader sees first (bold in Markdown,
  // a larger paragraph of class "lead" in HTML).
  void lead(const std::string& text);
  // Adds a bulleted list.
  void bullets(const std::vector<std::string>& items);
  // Adds a table; every row has header.size() cells.
  void table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows);
  // Adds a figure: name is its file stem (name.svg), svg its text.
  void figure(const std::string& name, const std::string& caption, const std::string& svg);
  // Adds preformatted text.
  void preformatted(const std::string& text);

  // Markdown text; figures referenced as "<name>.svg" in the same folder.
  std::string markdown() const;
  // Self-contained HTML page with inline SVG figures and a small stylesheet.
  std::string html(const std::string& title) const;
  // The figures as (file name, SVG text) pairs.
  std::vector<std::pair<std::string, std::string>> figure_files() const;
  // Stages STEM.md, STEM.html (titled title) and the figures in out (the
  // staged folder of models/output_file.hpp: all files or none at commit).
  void stage(OutputFolder& out, const std::string& stem, const std::string& title) const;

 private:
  struct Block {
    enum class Kind { kHeading, kParagraph, kLead, kBullets, kTable, kFigure, kPre } kind;
    int level = 0;
    std::string text;                            // heading, paragraph, caption, pre
    std::string name, svg;                       // figure
    std::vector<std::string> header;             // table header or bullet items
    std::vector<std::vector<std::string>> rows;  // table rows
  };
  std::vector<Block> blocks_;
};

// A table cell or header as GitHub-flavoured Markdown writes it: `|` escaped
// as `\|` and line breaks as spaces, so every row keeps its cell count.
std::string markdown_cell(const std::string& text);

// Text written in ASCII (the run library's notes and lines, as an ASCII
// terminal shows them) with its units as symbols: "28.15 um" -> "28.15 µm"
// and "urad" -> "µrad" after a number, the word "chi2" -> "χ²" ("chi2/dof"
// -> "χ²/dof"); nothing else changed.
std::string unit_symbols(const std::string& text);

// Text written for a terminal (units in ASCII, C exponents, "x" for times)
// as a report shows it: "28.15 um" -> "28.15 µm" (and urad, after a
// number), "7.31e-05" -> "7.31×10⁻⁵", "x2.63" -> "×2.63", "5.3x the" -> "5.3× the".
std::string readable_text(const std::string& text);

// Escaped HTML of text with `code` spans set as <code>, the rest as
// readable_text shows it (the Markdown keeps numbers as machines read them).
std::string inline_html(const std::string& text);

}  // namespace gpm::report
