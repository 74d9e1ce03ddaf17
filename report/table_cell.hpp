// A number as a report's text or table cell shows it: "-" for a number not
// measured, a few significant digits, never the C exponent notation
// ("1.05e+03") a reader must decode.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

namespace gpm::report {

// v formatted by f (an fmt format, e.g. "{:.2f}"), or "-" when v is not finite.
inline std::string table_cell(double v, const char* f) {
  return std::isfinite(v) ? fmt::format(fmt::runtime(f), v) : "-";
}

// v with `digits` significant digits in fixed notation, never fewer than its
// whole digits (9712.3 -> "9712", 9.263 -> "9.26", 0.01274 -> "0.0127");
// "-" when v is not finite.
inline std::string sig(double v, int digits = 3) {
  if (!std::isfinite(v)) return "-";
  if (v == 0.0) return "0";
  int whole = static_cast<int>(std::floor(std::log10(std::abs(v)))) + 1;
  // 99.99 at 3 digits rounds to 100, a digit more before the point: "100", not "100.0".
  if (std::abs(std::stod(fmt::format("{:.{}f}", v, std::clamp(digits - whole, 0, 12)))) >= std::pow(10.0, whole))
    ++whole;
  const std::string s = fmt::format("{:.{}f}", v, std::clamp(digits - whole, 0, 12));
  return s == "-0" ? "0" : s;
}

// v with `digits` significant digits: fixed notation between 1e-3 and 1e6,
// else a power of ten in Unicode ("1.05×10⁻⁷"); "-" when v is not finite.
inline std::string sci(double v, int digits = 3) {
  if (!std::isfinite(v)) return "-";
  const double a = std::abs(v);
  if (a == 0.0 || (a >= 1e-3 && a < 1e6)) return sig(v, digits);
  int e = static_cast<int>(std::floor(std::log10(a)));
  const int decimals = std::max(0, digits - 1);
  // 9.999e-5 at 3 digits rounds to 1.00e-4, not 10.0e-5.
  if (std::abs(std::stod(fmt::format("{:.{}f}", v / std::pow(10.0, e), decimals))) >= 10.0) ++e;
  const std::string mantissa = fmt::format("{:.{}f}", v / std::pow(10.0, e), decimals);
  static const char* const kSup[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
  std::string exponent = e < 0 ? "⁻" : "";
  for (const char c : std::to_string(std::abs(e))) exponent += kSup[c - '0'];
  return mantissa + "×10" + exponent;
}

// v to a tenth of its 1-sigma (sigma 1e-3 -> 4 decimals); without a usable
// sigma, up to 8 significant digits, trailing zeros dropped.
inline std::string value_to_sigma(double v, double sigma) {
  if (!std::isfinite(v)) return "-";
  if (!(std::isfinite(sigma) && sigma > 0.0))
    return v == 0.0 || (std::abs(v) >= 1e-3 && std::abs(v) < 1e6) ? fmt::format("{:.8g}", v) : sci(v, 8);
  return fmt::format("{:.{}f}", v, std::clamp(static_cast<int>(std::ceil(-std::log10(sigma))) + 1, 0, 10));
}

// A ratio as a reader compares it: 3 significant digits below 1000, whole
// numbers above ("1046", not "1.05e+03").
inline std::string ratio_text(double v) { return sig(v, 3); }

}  // namespace gpm::report
