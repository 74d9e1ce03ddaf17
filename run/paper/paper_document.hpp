// The document of `gpm paper`: DIR/paper.md (figures as SVG files beside
// it), DIR/paper.html (report/ReportDocument) and DIR/paper.json with the same
// numbers. Every table shows the paper's printed value beside this run's;
// every difference points to a numbered sentence saying why.
#pragma once

#include <string>

#include "report/report_document.hpp"
#include "run/paper/paper_run.hpp"

namespace gpm {
class OutputFolder;
}

namespace gpm::paper {

// The document: a summary, then one section per table or figure with its
// setup, the side-by-side table, the numbered reasons and the findings.
report::ReportDocument paper_document(const PaperRun& run);

// paper.json: {"budget", "seed", "seconds", "tables": [{"id", "title",
// "setup", "extra_column", "notes", "rows": [{"quantity", "unit", "paper"
// (number or null), "paper_text", "ours" (number or null), "ours_text",
// "extra", "difference" (number or null), "reason", "why"}]}]}.
std::string paper_json(const PaperRun& run);

// Stages paper.md, paper.html, the figures and paper.json in out (committed by the caller).
void stage_paper(const PaperRun& run, OutputFolder& out);

// Writes paper.md, paper.html, the figures and paper.json into dir, all or
// none (models/output_file.hpp). Throws InputError when dir cannot be written.
void write_paper(const PaperRun& run, const std::string& dir);

// The reason cell of a row in paper.md: "agrees" or "[n] <reason name>",
// n numbering the distinct sentences of its table from 1.
std::string reason_cell(const Table& table, const Row& row);

}  // namespace gpm::paper
