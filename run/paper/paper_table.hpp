// One table (or figure) of the paper reproduced: for each printed quantity the
// paper's value, this run's value and, when they differ, the sentence saying
// why. Built by run/paper/section*.hpp, written by run/paper/paper_document.hpp.
#pragma once

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "report/paper_report.hpp"

namespace gpm::paper {

// Why a value differs from the printed one, a row and a table (report/paper_report.hpp).
using Reason = report::PaperReason;
using Row = report::PaperRow;
using Table = report::PaperTable;

// "agrees", "paper mistake", "property of the method", "different setup", "open question".
const char* reason_name(Reason r);

// A table with its id, title and setup paragraph, no rows yet.
Table make_table(const std::string& id, const std::string& title, const std::string& setup);

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
