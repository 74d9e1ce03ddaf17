#include "run/paper/paper_document.hpp"

#include <algorithm>
#include <map>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "models/output_file.hpp"

namespace gpm::paper {

namespace {

// The distinct sentences of a table's differing rows, in order of first use.
std::vector<std::string> sentences(const Table& t) {
  std::vector<std::string> s;
  for (const Row& r : t.rows) {
    if (r.reason == Reason::kAgrees || r.why.empty()) continue;
    if (std::find(s.begin(), s.end(), r.why) == s.end()) s.push_back(r.why);
  }
  return s;
}

std::string difference_text(const Row& r) {
  if (!r.paper || !r.ours) return "";
  const double d = *r.ours - *r.paper;
  return (d > 0 ? "+" : "") + format_value(d);
}

struct Counts {
  int rows = 0, compared = 0, agree = 0;
  std::map<Reason, int> by_reason;
};

Counts count(const Table& t) {
  Counts c;
  for (const Row& r : t.rows) {
    ++c.rows;
    if (r.paper) ++c.compared;
    if (r.reason == Reason::kAgrees) ++c.agree;
    else ++c.by_reason[r.reason];
  }
  return c;
}

}  // namespace

std::string reason_cell(const Table& table, const Row& row) {
  if (row.reason == Reason::kAgrees) return "agrees";
  const auto s = sentences(table);
  const auto it = std::find(s.begin(), s.end(), row.why);
  return fmt::format("[{}] {}", it - s.begin() + 1, reason_name(row.reason));
}

report::ReportDocument paper_document(const PaperRun& run) {
  report::ReportDocument d;
  d.heading(1, "The paper reproduced: printed values beside this run's");
  d.paragraph(fmt::format(
      "Every experiment of the chapter (docs/PAPER_NOTES.md) run as the paper ran it, on the MuJoCo twin "
      "(Tables 1 and 8, the paper's real robot) or on generated data (Tables 2-7, the paper's simulations), "
      "with the corrections of docs/PAPER_NOTES.md applied. Budget {:.3g} error-function evaluations per "
      "GA/PSO/DE run (the paper: 5e7; `gpm paper --budget 5e7`), seed {}, {:.0f} s. Each row gives the printed "
      "value, this run's, their difference and why they differ; the numbered sentences under each table say "
      "why. Reasons: paper mistake (an erratum), property of the method (what the mathematics or the solver "
      "does), different setup (the paper's robot, samples or budget are not available), open question.",
      static_cast<double>(run.settings.budget), run.settings.seed, run.seconds));
  std::vector<std::vector<std::string>> summary;
  for (const Table& t : run.tables) {
    const Counts c = count(t);
    std::string reasons;
    for (const auto& [r, n] : c.by_reason) reasons += fmt::format("{}{} {}", reasons.empty() ? "" : ", ", n, reason_name(r));
    summary.push_back({t.title.substr(0, t.title.find('.')), std::to_string(c.rows), std::to_string(c.agree),
                       reasons.empty() ? "-" : reasons});
  }
  d.table({"table or figure", "rows", "agree", "differences and why"}, summary);
  for (const Table& t : run.tables) {
    d.heading(2, t.title);
    d.paragraph(t.setup);
    if (!t.figure_svg.empty()) d.figure(t.id, t.title + " (this run)", t.figure_svg);
    std::vector<std::string> header{"quantity", "unit", "paper", "this run"};
    if (!t.extra_column.empty()) header.push_back(t.extra_column);
    header.push_back("difference");
    header.push_back("why");
    std::vector<std::vector<std::string>> rows;
    for (const Row& r : t.rows) {
      std::vector<std::string> cells{r.quantity, r.unit, r.paper_text, r.ours_text};
      if (!t.extra_column.empty()) cells.push_back(r.extra_text);
      cells.push_back(difference_text(r));
      cells.push_back(reason_cell(t, r));
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

std::string paper_json(const PaperRun& run) {
  using nlohmann::json;
  auto num = [](const std::optional<double>& v) -> json {
    if (!v || !std::isfinite(*v)) return nullptr;
    return *v;
  };
  json j;
  j["budget"] = run.settings.budget;
  j["table8_evaluations"] = run.settings.table8_evaluations;
  j["seed"] = run.settings.seed;
  j["seconds"] = run.seconds;
  j["tables"] = json::array();
  for (const Table& t : run.tables) {
    json jt;
    jt["id"] = t.id;
    jt["title"] = t.title;
    jt["setup"] = t.setup;
    jt["extra_column"] = t.extra_column;
    jt["notes"] = t.notes;
    jt["figure"] = t.figure_svg.empty() ? json(nullptr) : json(t.id + ".svg");
    jt["rows"] = json::array();
    for (const Row& r : t.rows) {
      json jr;
      jr["quantity"] = r.quantity;
      jr["unit"] = r.unit;
      jr["paper"] = num(r.paper);
      jr["paper_text"] = r.paper_text;
      jr["ours"] = num(r.ours);
      jr["ours_text"] = r.ours_text;
      jr["extra"] = r.extra_text;
      jr["difference"] = (r.paper && r.ours) ? num(*r.ours - *r.paper) : json(nullptr);
      jr["reason"] = reason_name(r.reason);
      jr["why"] = r.why;
      jt["rows"].push_back(jr);
    }
    j["tables"].push_back(jt);
  }
  return j.dump(1) + "\n";
}

void stage_paper(const PaperRun& run, OutputFolder& out) {
  paper_document(run).stage(out, "paper", "The paper reproduced");
  out.add("paper.json", paper_json(run));
}

void write_paper(const PaperRun& run, const std::string& dir) {
  OutputFolder out(dir);
  stage_paper(run, out);
  out.commit();
}

}  // namespace gpm::paper
