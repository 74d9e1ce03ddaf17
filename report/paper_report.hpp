// The document of `gpm paper` (paper.md and paper.html): a summary, then
// one section per table or figure of the paper with its setup, the printed
// values beside this run's, the numbered reasons and the findings, from
// plain data (the tables run/paper builds).
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "report/report_document.hpp"

namespace gpm::report {

// Why a value differs from the printed one.
enum class PaperReason {
  kAgrees,        // equal to the printed digits (no sentence needed)
  kPaperMistake,  // the printed value is wrong (docs/PAPER_NOTES.md, an errata item)
  kMethod,        // a property of the method or of the solver
  kSetup,         // a different setup: the paper's data, robot or budget are not reproduced exactly
  kOpen,          // not explained: an open question
};

// "agrees", "paper mistake", "property of the method", "different setup", "open question".
const char* paper_reason_name(PaperReason r);

// One printed quantity: the paper's value, this run's, and why they differ.
struct PaperRow {
  std::string quantity;            // e.g. "dth1, J1, 3 samples"
  std::string unit;                // "rad", "mm", "" ...
  std::optional<double> paper;     // printed value (nullopt: not printed)
  std::string paper_text;          // as printed ("-" when not printed)
  std::optional<double> ours;      // this run's value (nullopt: text only)
  std::string ours_text;           // as written in paper.md
  std::string extra_text;          // the table's extra column (e.g. the actual value), may be empty
  PaperReason reason = PaperReason::kAgrees;
  std::string why;                 // one sentence; empty only when reason is kAgrees
};

// One table (or figure) of the paper reproduced, row by row.
struct PaperTable {
  std::string id;                  // "table1" ... "table8", "figure3" ... "figure5"
  std::string title;               // e.g. "Table 2. Calibration results of sensor zero positions"
  std::string setup;               // what this run did, as the paper did it (one paragraph)
  std::string extra_column;        // header of PaperRow::extra_text ("" = no extra column)
  std::vector<PaperRow> rows;
  std::string figure_svg;          // figures: the SVG of this run (empty for tables)
  std::vector<std::string> notes;  // findings that are not one row (sentences)
};

// Value printed the way paper.md and paper.json show it: 6 significant digits.
std::string paper_value_text(double v);

// Everything the paper document shows.
struct PaperDocument {
  long budget = 0;          // evaluations per GA/PSO/DE run
  std::uint64_t seed = 0;
  double seconds = 0.0;
  std::vector<PaperTable> tables;
};

// The reason cell of a row in paper.md: "agrees" or "[n] <reason name>",
// n numbering the distinct sentences of its table from 1.
std::string paper_reason_cell(const PaperTable& table, const PaperRow& row);

// One run's convergence record on a figure: (evaluations, best J) after each improvement.
struct PaperCurve {
  std::string label;  // the method, e.g. "DE"
  std::vector<std::pair<long, double>> history;
};

// Figure 3, 4 or 5 of the paper: best J (cost, e.g. "J1") against evaluations, log y, one line per curve.
std::string paper_convergence_svg(int figure, const std::string& cost, const std::vector<PaperCurve>& curves);

// The document: a summary, then one section per table or figure.
ReportDocument paper_document(const PaperDocument& p);

}  // namespace gpm::report
