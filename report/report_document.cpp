#include "report/report_document.hpp"

#include <cctype>
#include <regex>

#include <fmt/format.h>

#include "report/svg_plot.hpp"
#include "report/table_cell.hpp"
#include "models/output_file.hpp"

namespace gpm::report {

void ReportDocument::heading(int level, const std::string& text) {
  blocks_.push_back({Block::Kind::kHeading, level, text, {}, {}, {}, {}});
}
void ReportDocument::paragraph(const std::string& text) {
  blocks_.push_back({Block::Kind::kParagraph, 0, text, {}, {}, {}, {}});
}
void ReportDocument::lead(const std::string& text) {
  blocks_.push_back({Block::Kind::kLead, 0, text, {}, {}, {}, {}});
}
void ReportDocument::bullets(const std::vector<std::string>& items) {
  blocks_.push_back({Block::Kind::kBullets, 0, {}, {}, {}, items, {}});
}
void ReportDocument::table(const std::vector<std::string>& header,
                           const std::vector<std::vector<std::string>>& rows) {
  blocks_.push_back({Block::Kind::kTable, 0, {}, {}, {}, header, rows});
}
void ReportDocument::figure(const std::string& name, const std::string& caption, const std::string& svg) {
  blocks_.push_back({Block::Kind::kFigure, 0, caption, name, svg, {}, {}});
}
void ReportDocument::preformatted(const std::string& text) {
  blocks_.push_back({Block::Kind::kPre, 0, text, {}, {}, {}, {}});
}

std::string unit_symbols(const std::string& text) {
  std::string out;
  for (size_t i = 0; i < text.size(); ++i) {
    const bool after_number = !out.empty() && (std::isdigit(static_cast<unsigned char>(out.back())) ||
                                               (out.back() == ' ' && out.size() > 1 &&
                                                std::isdigit(static_cast<unsigned char>(out[out.size() - 2]))));
    for (const char* unit : {"urad", "um"}) {
      const std::string u = unit;
      const size_t end = i + u.size();
      const bool whole = end == text.size() || !std::isalnum(static_cast<unsigned char>(text[end]));
      if (after_number && whole && text.compare(i, u.size(), u) == 0) {
        out += "µ" + u.substr(1);
        i = end;
        break;
      }
    }
    if (i < text.size()) out += text[i];
  }
  static const std::regex chi2(R"(\bchi2\b)");  // a word: "chi2/dof", not "model_test_chi2"
  return std::regex_replace(out, chi2, "χ²");
}

std::string readable_text(const std::string& text) {
  static const std::regex number(R"((^|[^0-9A-Za-z_.])(-?[0-9]+(?:\.[0-9]+)?)e([+-]?[0-9]+)\b)");
  std::string out;
  auto at = text.cbegin();
  for (std::sregex_iterator m(text.begin(), text.end(), number), end; m != end; ++m) {
    const std::smatch& g = *m;
    const double v = std::stod(g[2].str() + "e" + g[3].str());
    const size_t shown = g[2].str().find('.') == std::string::npos ? 1 : g[2].str().size() - g[2].str().find('.');
    out.append(at, g[0].first).append(g[1].str()).append(sci(v, static_cast<int>(std::max<size_t>(1, shown))));
    at = g[0].second;
  }
  out.append(at, text.cend());
  // "x2.63" and "5.32x the" are ratios: "×2.63", "5.32× the".
  static const std::regex times_before(R"((^|[\s(])x([0-9]))"), times_after(R"(([0-9])x(\s|$|[,;:)]))");
  out = std::regex_replace(std::regex_replace(out, times_before, "$1×$2"), times_after, "$1×$2");
  return unit_symbols(out);
}

std::string markdown_cell(const std::string& text) {
  std::string out;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '|' && (i == 0 || text[i - 1] != '\\')) out += "\\|";
    else if (c == '\n' || c == '\r') out += ' ';
    else out += c;
  }
  return out;
}

std::string inline_html(const std::string& text) {
  std::string out;
  size_t at = 0;
  for (size_t open = text.find('`'); open != std::string::npos; open = text.find('`', at)) {
    const size_t close = text.find('`', open + 1);
    if (close == std::string::npos) break;  // an unpaired backtick stays as text
    out += xml_escape(readable_text(text.substr(at, open - at))) + "<code>" +
           xml_escape(text.substr(open + 1, close - open - 1)) + "</code>";
    at = close + 1;
  }
  return out + xml_escape(readable_text(text.substr(at)));
}

namespace {

// A heading's HTML: inline_html with a line-break opportunity after each '_'
// and '/', so a long scenario or file name splits there, not inside a word.
std::string heading_html(const std::string& text) {
  std::string out;
  bool in_tag = false;
  for (const char c : inline_html(text)) {
    out += c;
    in_tag = c == '<' || (in_tag && c != '>');
    if (!in_tag && (c == '_' || c == '/')) out += "<wbr>";
  }
  return out;
}

}  // namespace

std::string ReportDocument::markdown() const {
  std::string md;
  for (const Block& b : blocks_) {
    switch (b.kind) {
      case Block::Kind::kHeading: md += std::string(static_cast<size_t>(b.level), '#') + " " + b.text + "\n\n"; break;
      case Block::Kind::kParagraph: md += b.text + "\n\n"; break;
      case Block::Kind::kLead: md += "**" + b.text + "**\n\n"; break;
      case Block::Kind::kBullets:
        for (const auto& item : b.header) md += "- " + item + "\n";
        md += "\n";
        break;
      case Block::Kind::kTable: {
        md += "|";
        for (const auto& h : b.header) md += " " + markdown_cell(h) + " |";
        md += "\n|";
        for (size_t i = 0; i < b.header.size(); ++i) md += " --- |";
        md += "\n";
        for (const auto& row : b.rows) {
          md += "|";
          for (size_t k = 0; k < b.header.size(); ++k) md += " " + (k < row.size() ? markdown_cell(row[k]) : "") + " |";
          md += "\n";
        }
        md += "\n";
        break;
      }
      case Block::Kind::kFigure: md += fmt::format("![{}]({}.svg)\n\n*{}*\n\n", b.text, b.name, b.text); break;
      case Block::Kind::kPre: md += "```\n" + b.text + (b.text.ends_with('\n') ? "" : "\n") + "```\n\n"; break;
    }
  }
  return md;
}

std::string ReportDocument::html(const std::string& title) const {
  std::string h = fmt::format(
      "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\"><title>{}</title>\n"
      // Tables fit the page where they can: headers wrap at spaces, text cells
      // (those with a space) wrap anywhere if they must, numbers never break;
      // narrow windows get a smaller table font, and a table still too wide
      // scrolls inside its own container (div.scroll), never the page.
      // Figures scale down with the page; headings split after '_' and '/'.
      "<style>body{{font-family:sans-serif;max-width:980px;margin:2em auto;padding:0 1em;color:#222;"
      "line-height:1.4;overflow-wrap:break-word}}"
      "div.scroll{{overflow-x:auto;max-width:100%;margin:1em 0}}"
      "table{{border-collapse:collapse;font-size:.9em}}"
      "td,th{{border:1px solid #ccc;padding:3px 6px;text-align:right;vertical-align:top;"
      "font-variant-numeric:tabular-nums}}th{{background:#f3f3f3;font-weight:600}}"
      "td:first-child,th:first-child{{text-align:left}}td.t,th.t{{text-align:left;overflow-wrap:anywhere;min-width:6em}}"
      "figure{{margin:1.5em 0}}figure>svg{{display:block;max-width:100%;height:auto}}"
      "figcaption{{font-style:italic;color:#555}}"
      "pre{{background:#f6f6f6;padding:.6em;white-space:pre-wrap;overflow-wrap:anywhere}}"
      "code{{background:#f3f3f3;padding:0 .2em;border-radius:3px;font-size:.92em}}"
      "p.lead{{font-size:1.2em;line-height:1.45;margin:.8em 0}}"
      "@media (max-width:820px){{table{{font-size:.78em}}td,th{{padding:2px 4px}}}}"
      "@media (max-width:600px){{body{{margin:1em auto}}h1{{font-size:1.5em}}h2{{font-size:1.25em}}p.lead{{font-size:1.1em}}}}"
      "</style></head><body>\n",
      xml_escape(title));
  for (const Block& b : blocks_) {
    switch (b.kind) {
      case Block::Kind::kHeading: h += fmt::format("<h{0}>{1}</h{0}>\n", b.level, heading_html(b.text)); break;
      case Block::Kind::kParagraph: h += "<p>" + inline_html(b.text) + "</p>\n"; break;
      case Block::Kind::kLead: h += "<p class=\"lead\">" + inline_html(b.text) + "</p>\n"; break;
      case Block::Kind::kBullets:
        h += "<ul>";
        for (const auto& item : b.header) h += "<li>" + inline_html(item) + "</li>";
        h += "</ul>\n";
        break;
      case Block::Kind::kTable:
      {
        h += "<div class=\"scroll\"><table><tr>";
        // A column of text cells (class t, left-aligned) gets a left-aligned header.
        for (size_t k = 0; k < b.header.size(); ++k) {
          bool text = false;
          for (const auto& row : b.rows) text = text || (k < row.size() && row[k].find(' ') != std::string::npos);
          h += (text && k > 0 ? "<th class=\"t\">" : "<th>") + inline_html(b.header[k]) + "</th>";
        }
        h += "</tr>\n";
        for (const auto& row : b.rows) {
          h += "<tr>";
          for (const auto& c : row) h += (c.find(' ') == std::string::npos ? "<td>" : "<td class=\"t\">") + inline_html(c) + "</td>";
          h += "</tr>\n";
        }
        h += "</table></div>\n";
        break;
      }
      case Block::Kind::kFigure:
        h += "<figure id=\"fig-" + xml_escape(b.name) + "\">" + b.svg + "<figcaption>" + inline_html(b.text) +
             "</figcaption></figure>\n";
        break;
      case Block::Kind::kPre: h += "<pre>" + xml_escape(b.text) + "</pre>\n"; break;
    }
  }
  h += "</body></html>\n";
  return h;
}

std::vector<std::pair<std::string, std::string>> ReportDocument::figure_files() const {
  std::vector<std::pair<std::string, std::string>> out;
  for (const Block& b : blocks_) {
    if (b.kind == Block::Kind::kFigure) out.emplace_back(b.name + ".svg", b.svg);
  }
  return out;
}

void ReportDocument::stage(OutputFolder& out, const std::string& stem, const std::string& title) const {
  out.add(stem + ".md", markdown());
  out.add(stem + ".html", html(title));
  for (const auto& [name, svg] : figure_files()) out.add(name, svg);
}

}  // namespace gpm::report
