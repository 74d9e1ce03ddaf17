#include "run/paper/paper_document.hpp"

#include <cmath>

#include <nlohmann/json.hpp>

#include "models/output_file.hpp"

namespace gpm::paper {

std::string reason_cell(const Table& table, const Row& row) { return report::paper_reason_cell(table, row); }

report::ReportDocument paper_document(const PaperRun& run) {
  return report::paper_document({run.settings.budget, run.settings.seed, run.seconds, run.tables});
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
