// Checks of a report's text shared by the tests of report/ (report_document,
// run_report, monitor_report, paper_report): every GitHub-flavoured Markdown
// table has as many cells in each row as in its header, and the HTML page
// shows no Markdown syntax or machine number formats as text.
#pragma once

#include <regex>
#include <sstream>
#include <utility>
#include <string>
#include <vector>

namespace gpm::report::testing {

// The cells of a GFM table row: split at '|' not escaped by '\', the
// leading and trailing pipe dropped (GFM counts cells so).
inline std::vector<std::string> gfm_cells(const std::string& line) {
  std::vector<std::string> cells{""};
  for (size_t i = 0; i < line.size(); ++i) {
    if (line[i] == '\\' && i + 1 < line.size()) {
      cells.back() += line.substr(i, 2);
      ++i;
    } else if (line[i] == '|') {
      cells.emplace_back();
    } else {
      cells.back() += line[i];
    }
  }
  const auto blank = [](const std::string& c) { return c.find_first_not_of(" \t") == std::string::npos; };
  if (!cells.empty() && blank(cells.front()) && line.find_first_not_of(" \t") != std::string::npos &&
      line[line.find_first_not_of(" \t")] == '|')
    cells.erase(cells.begin());
  if (!cells.empty() && blank(cells.back()) && line.find_last_not_of(" \t") != std::string::npos &&
      line[line.find_last_not_of(" \t")] == '|')
    cells.pop_back();
  return cells;
}

// Whether line is a GFM delimiter row (| --- | :---: | ...).
inline bool gfm_delimiter_row(const std::string& line) {
  static const std::regex row(R"(^\s*\|?\s*:?-+:?\s*(\|\s*:?-+:?\s*)*\|?\s*$)");
  return std::regex_match(line, row);
}

// Every table of md whose rows do not have its header's cell count (and
// headers whose delimiter row differs), one line each; empty when all agree.
// The number of tables found is added to *tables.
inline std::vector<std::string> markdown_table_errors(const std::string& md, int* tables = nullptr) {
  std::vector<std::string> lines, errors;
  std::istringstream in(md);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  for (size_t i = 0; i + 1 < lines.size(); ++i) {
    if (lines[i].find('|') == std::string::npos || !gfm_delimiter_row(lines[i + 1])) continue;
    if (tables) ++*tables;
    const size_t n = gfm_cells(lines[i]).size();
    if (gfm_cells(lines[i + 1]).size() != n)
      errors.push_back("header of " + std::to_string(n) + " cells, delimiter row of " +
                       std::to_string(gfm_cells(lines[i + 1]).size()) + ": " + lines[i]);
    size_t j = i + 2;
    for (; j < lines.size() && lines[j].find('|') != std::string::npos; ++j)
      if (gfm_cells(lines[j]).size() != n)
        errors.push_back("row of " + std::to_string(gfm_cells(lines[j]).size()) + " cells under a header of " +
                         std::to_string(n) + ": " + lines[j]);
    i = j - 1;
  }
  return errors;
}

// The text a reader sees of an HTML page: figures (svg), style, script and
// code spans left out, tags removed, entities kept as written.
inline std::string visible_html_text(const std::string& html) {
  // By hand, not std::regex: the figures make pages of a megabyte.
  std::string t;
  for (size_t at = 0; at < html.size();) {
    if (html[at] != '<') {
      t += html[at++];
      continue;
    }
    bool skipped = false;
    for (const std::string tag : {"svg", "style", "script", "code", "pre"}) {
      if (html.compare(at + 1, tag.size(), tag) != 0) continue;
      const char next = at + 1 + tag.size() < html.size() ? html[at + 1 + tag.size()] : '>';
      if (next != '>' && next != ' ' && next != '\n') continue;
      // The matching close tag (an svg_stack nests <svg> in <svg>).
      int depth = 0;
      size_t p = at;
      while (p < html.size()) {
        const size_t open = html.find("<" + tag, p + 1), close = html.find("</" + tag + ">", p + 1);
        if (close == std::string::npos) {
          p = html.size();
          break;
        }
        if (open < close) {
          ++depth, p = open;
        } else if (depth-- == 0) {
          p = close + tag.size() + 3;
          break;
        } else {
          p = close;
        }
      }
      at = p;
      skipped = true;
      break;
    }
    if (skipped) {
      t += ' ';
      continue;
    }
    const size_t close = html.find('>', at);
    at = close == std::string::npos ? html.size() : close + 1;
    t += ' ';
  }
  return t;
}

// What of Markdown or machine formatting shows as text on the HTML page, one
// line each: backticks, emphasis, links and images, escaped pipes, table
// rules, C exponents ("1.05e+03") and ASCII units after a number ("9.3 um").
inline std::vector<std::string> leaked_markdown(const std::string& html) {
  const std::string text = visible_html_text(html);
  std::vector<std::string> found;
  const std::vector<std::pair<std::string, std::regex>> patterns{
      {"backtick", std::regex("`")},
      {"emphasis", std::regex(R"(\*\*|(^|\s)_[^_\s][^_]*_(\s|$))")},
      {"link or image", std::regex(R"(\]\(|!\[)")},
      {"escaped pipe", std::regex(R"(\\\|)")},
      {"table rule", std::regex(R"(\|\s*---)")},
      {"heading mark", std::regex(R"((^|\n)\s*#{1,6} )")},
      {"C exponent", std::regex(R"([0-9]\.?[0-9]*e[+-][0-9]+)")},
      {"ASCII unit", std::regex(R"([0-9] ?u(m|rad|s)\b)")},
  };
  for (const auto& [name, re] : patterns) {
    std::smatch m;
    if (std::regex_search(text, m, re)) {
      const size_t at = static_cast<size_t>(m.position(0));
      const size_t from = at > 40 ? at - 40 : 0;
      found.push_back(name + ": ..." + text.substr(from, 80) + "...");
    }
  }
  return found;
}

}  // namespace gpm::report::testing
