// One table (or figure) of the paper reproduced: for each printed quantity the
// paper's value, this run's value and, when they differ, the sentence saying
// why. Built by run/paper/section*.hpp, written by run/paper/paper_document.hpp.
#pragma once

#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace gpm::paper {

// Why a value differs from the printed one.
enum class Reason {
  kAgrees,        // equal to the printed digits (no sentence needed)
  kPaperMistake,  // the printed value is wrong (docs/PAPER_NOTES.md, an errata item)
  kMethod,        // a property of the method or of the solver
  kSetup,         // a different setup: the paper's data, robot or budget are not reproduced exactly
  kOpen,          // not explained: an open question
};

// "agrees", "paper mistake", "property of the method", "different setup", "open question".
const char* reason_name(Reason r);

struct Row {
  std::string quantity;            // e.g. "dth1, J1, 3 samples"
  std::string unit;                // "rad", "mm", "" ...
  std::optional<double> paper;     // printed value (nullopt: not printed)
  std::string paper_text;          // as printed ("-" when not printed)
  std::optional<double> ours;      // this run's value (nullopt: text only)
  std::string ours_text;           // as written in paper.md
  std::string extra_text;          // the table's extra column (e.g. the actual value), may be empty
  Reason reason = Reason::kAgrees;
  std::string why;                 // one sentence; empty only when reason is kAgrees
};

struct Table {
  std::string id;                  // "table1" ... "table8", "figure3" ... "figure5"
  std::string title;               // e.g. "Table 2. Calibration results of sensor zero positions"
  std::string setup;               // what this run did, as the paper did it (one paragraph)
  std::string extra_column;        // header of Row::extra_text ("" = no extra column)
  std::vector<Row> rows;
  std::string figure_svg;          // figures: the SVG of this run (empty for tables)
  std::vector<std::string> notes;  // findings that are not one row (sentences)
};

// Value printed the way paper.md and paper.json show it: 6 significant digits.
std::string format_value(double v);

// Digits printed: the half-unit of the last printed digit of text ("1.00078"
// -> 5e-6, "3.1841e2" -> 5e-3); 0 when text has no digits.
double printed_half_unit(const std::string& text);

// A row comparing a printed value with ours. Agrees (reason kAgrees, no
// sentence) when |ours - paper| is within the printed half-unit (or within
// abs_tol when larger); otherwise takes reason and why.
Row compare_row(const std::string& quantity, const std::string& unit, const std::string& paper_text,
                double ours, Reason reason, const std::string& why, double abs_tol = 0.0);

// A row with a printed value the run has no counterpart of, or ours only.
Row text_row(const std::string& quantity, const std::string& unit, const std::string& paper_text,
             const std::string& ours_text, Reason reason, const std::string& why);

}  // namespace gpm::paper
