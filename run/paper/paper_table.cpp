#include "run/paper/paper_table.hpp"

#include <cctype>
#include <cstdlib>

#include <fmt/format.h>

namespace gpm::paper {

const char* reason_name(Reason r) { return report::paper_reason_name(r); }

Table make_table(const std::string& id, const std::string& title, const std::string& setup) {
  return Table{id, title, setup, {}, {}, {}, {}};
}

std::string format_value(double v) { return report::paper_value_text(v); }

double printed_half_unit(const std::string& text) {
  // Mantissa decimals and exponent: "1.00078" -> 5 decimals, "3.1841e2" -> 4 decimals, e2.
  const size_t e = text.find_first_of("eE");
  const std::string mant = text.substr(0, e);
  const int exp = e == std::string::npos ? 0 : std::atoi(text.c_str() + e + 1);
  bool digit = false;
  for (char c : mant) digit = digit || std::isdigit(static_cast<unsigned char>(c));
  if (!digit) return 0.0;
  const size_t dot = mant.find('.');
  const int decimals = dot == std::string::npos ? 0 : static_cast<int>(mant.size() - dot - 1);
  return 0.5 * std::pow(10.0, exp - decimals);
}

Row compare_row(const std::string& quantity, const std::string& unit, const std::string& paper_text,
                double ours, Reason reason, const std::string& why, double abs_tol) {
  Row r;
  r.quantity = quantity;
  r.unit = unit;
  r.paper_text = paper_text;
  r.paper = std::strtod(paper_text.c_str(), nullptr);
  r.ours = ours;
  r.ours_text = format_value(ours);
  const double tol = std::max(printed_half_unit(paper_text) * (1 + 1e-9), abs_tol);
  if (std::isfinite(ours) && std::fabs(ours - *r.paper) <= tol) {
    r.reason = Reason::kAgrees;
  } else {
    r.reason = reason;
    r.why = why;
  }
  return r;
}

Row text_row(const std::string& quantity, const std::string& unit, const std::string& paper_text,
             const std::string& ours_text, Reason reason, const std::string& why) {
  Row r;
  r.quantity = quantity;
  r.unit = unit;
  r.paper_text = paper_text;
  r.ours_text = ours_text;
  r.reason = reason;
  r.why = why;
  return r;
}

}  // namespace gpm::paper
