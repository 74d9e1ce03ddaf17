#include "report/paper_report.hpp"

#include <algorithm>
#include <map>

#include <fmt/format.h>

#include "report/svg_plot.hpp"
#include "report/table_cell.hpp"

namespace gpm::report {

const char* paper_reason_name(PaperReason r) {
  switch (r) {
    case PaperReason::kAgrees: return "agrees";
    case PaperReason::kPaperMistake: return "paper mistake";
    case PaperReason::kMethod: return "property of the method";
    case PaperReason::kSetup: return "different setup";
    case PaperReason::kOpen: return "open question";
  }
  return "?";
}

std::string paper_value_text(double v) {
  if (!std::isfinite(v)) return std::isnan(v) ? "nan" : (v > 0 ? "inf" : "-inf");
  if (v == 0.0) return "0";
  const double a = std::fabs(v);
  if (a >= 1e-3 && a < 1e6) return fmt::format("{:.6g}", v);
  return fmt::format("{:.5e}", v);
}

namespace {

// The distinct sentences of a table's differing rows, in order of first use.
std::vector<std::string> sentences(const PaperTable& t) {
  std::vector<std::string> s;
  for (const PaperRow& r : t.rows) {
    if (r.reason == PaperReason::kAgrees || r.why.empty()) continue;
    if (std::find(s.begin(), s.end(), r.why) == s.end()) s.push_back(r.why);
  }
  return s;
}

std::string difference_text(const PaperRow& r) {
  if (!r.paper || !r.ours) return "";
  const double d = *r.ours - *r.paper;
  return (d > 0 ? "+" : "") + paper_value_text(d);
}

struct Counts {
  int rows = 0, compared = 0, agree = 0;
  std::map<PaperReason, int> by_reason;
};

Counts count(const PaperTable& t) {
  Counts c;
  for (const PaperRow& r : t.rows) {
    ++c.rows;
    if (r.paper) ++c.compared;
    if (r.reason == PaperReason::kAgrees) ++c.agree;
    else ++c.by_reason[r.reason];
  }
  return c;
}

}  // namespace

std::string paper_reason_cell(const PaperTable& table, const PaperRow& row) {
  if (row.reason == PaperReason::kAgrees) return "agrees";
  const auto s = sentences(table);
  const auto it = std::find(s.begin(), s.end(), row.why);
  return fmt::format("[{}] {}", it - s.begin() + 1, paper_reason_name(row.reason));
}

std::string paper_convergence_svg(int figure, const std::string& cost, const std::vector<PaperCurve>& curves) {
  std::vector<Series> series;
  for (const PaperCurve& c : curves) {
    Series s;
    s.label = c.label;
    for (const auto& [e, j] : c.history) {
      if (e <= 0 || !(j > 0)) continue;
      s.x.push_back(static_cast<double>(e));
      s.y.push_back(j);
    }
    series.push_back(std::move(s));
  }
  PlotOptions o = titled_plot(fmt::format("Figure {}: best {} against evaluations", figure, cost),
                              "error-function evaluations", cost);
  o.log_y = true;
  return svg_plot(series, o);
}

// The lead: how many printed values this run reproduces and why the others differ.
std::string paper_lead(const PaperDocument& p) {
  Counts all;
  for (const PaperTable& t : p.tables) {
    const Counts c = count(t);
    all.rows += c.rows, all.agree += c.agree;
    for (const auto& [r, n] : c.by_reason) all.by_reason[r] += n;
  }
  std::string why;
  for (const auto& [r, n] : all.by_reason) why += fmt::format("{}{}: {}", why.empty() ? "" : ", ", paper_reason_name(r), n);
  return fmt::format("Of the {} quantities of the paper's {} tables and figures reproduced here, {} agree with the "
                     "printed values{}.",
                     all.rows, p.tables.size(), all.agree,
                     why.empty() ? std::string() : "; the others differ for a stated reason (" + why + ")");
}

ReportDocument paper_document(const PaperDocument& p) {
  ReportDocument d;
  d.heading(1, "The paper reproduced: printed values beside this run's");
  d.lead(paper_lead(p));
  d.paragraph(fmt::format(
      "Every experiment of the chapter (docs/PAPER_NOTES.md) run as the paper ran it, on the MuJoCo twin "
      "(Tables 1 and 8, the paper's real robot) or on generated data (Tables 2-7, the paper's simulations), "
      "with the corrections of docs/PAPER_NOTES.md applied. Budget {} error-function evaluations per "
      "GA/PSO/DE run (the paper: 5×10⁷; `gpm paper --budget 5e7`), seed {}, {:.0f} s. Each row gives the printed "
      "value, this run's, their difference and why they differ; the numbered sentences under each table say "
      "why. Reasons: paper mistake (an erratum), property of the method (what the mathematics or the solver "
      "does), different setup (the paper's robot, samples or budget are not available), open question.",
      sci(static_cast<double>(p.budget), 2), p.seed, p.seconds));
  std::vector<std::vector<std::string>> summary;
  for (const PaperTable& t : p.tables) {
    const Counts c = count(t);
    std::string reasons;
    for (const auto& [r, n] : c.by_reason) reasons += fmt::format("{}{} {}", reasons.empty() ? "" : ", ", n, paper_reason_name(r));
    summary.push_back({t.title.substr(0, t.title.find('.')), std::to_string(c.rows), std::to_string(c.agree),
                       reasons.empty() ? "-" : reasons});
  }
  d.table({"table or figure", "rows", "agree", "differences and why"}, summary);
  for (const PaperTable& t : p.tables) {
    d.heading(2, t.title);
    d.paragraph(t.setup);
    if (!t.figure_svg.empty()) d.figure(t.id, t.title + " (this run)", t.figure_svg);
    std::vector<std::string> header{"quantity", "unit", "paper", "this run"};
    if (!t.extra_column.empty()) header.push_back(t.extra_column);
    header.push_back("difference");
    header.push_back("why");
    std::vector<std::vector<std::string>> rows;
    for (const PaperRow& r : t.rows) {
      std::vector<std::string> cells{r.quantity, r.unit, r.paper_text, r.ours_text};
      if (!t.extra_column.empty()) cells.push_back(r.extra_text);
      cells.push_back(difference_text(r));
      cells.push_back(paper_reason_cell(t, r));
      rows.push_back(std::move(cells));
    }
    d.table(header, rows);
    const auto s = sentences(t);
    if (!s.empty()) {
      std::vector<std::string> items;
      for (size_t i = 0; i < s.size(); ++i) items.push_back(fmt::format("[{}] {}", i + 1, s[i]));
      d.paragraph("Why the values differ:");
      d.bullets(items);
    }
    if (!t.notes.empty()) {
      d.paragraph("Findings:");
      d.bullets(t.notes);
    }
  }
  return d;
}

}  // namespace gpm::report
