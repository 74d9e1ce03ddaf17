// Numbers on the command line (app/number_options.hpp).
#include "app/number_options.hpp"

#include <charconv>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "app/cli_text.hpp"
#include "models/errors.hpp"

namespace gpm::cli {

CLI::Validator number_in(const Bound& b) {
  return CLI::Validator(
      [b](std::string& text) -> std::string {
        double v = 0.0;
        try {
          v = parse_bounded(text, b, "");
        } catch (const InputError& e) {
          std::string why = e.what();  // ": must be ..., got '...'" (no where: CLI11 names the flag)
          if (why.rfind(": ", 0) == 0) why = why.substr(2);
          const std::size_t at = why.find(text);
          if (text.size() > 40 && at != std::string::npos) why.replace(at, text.size(), cut(text));
          return why;
        }
        if (b.whole) text = fmt::format("{:.0f}", v);
        return "";
      },
      describe(b));
}

namespace {

// True for a number written in decimal: optional sign, digits with an
// optional fraction, an optional exponent (blanks around allowed). Not hex
// (0x1), binary (0b1), octal (0o1), digit separators (1_000, 1'000), nan, inf.
bool is_decimal(const std::string& text) {
  std::size_t i = text.find_first_not_of(" \t");
  const std::size_t last = text.find_last_not_of(" \t");
  if (i == std::string::npos) return false;
  const auto digit = [&](std::size_t k) { return k <= last && text[k] >= '0' && text[k] <= '9'; };
  if (text[i] == '+' || text[i] == '-') ++i;
  std::size_t digits = 0;
  for (; digit(i); ++i) ++digits;
  if (i <= last && text[i] == '.')
    for (++i; digit(i); ++i) ++digits;
  if (digits == 0) return false;
  if (i <= last && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    if (i <= last && (text[i] == '+' || text[i] == '-')) ++i;
    if (!digit(i)) return false;
    while (digit(i)) ++i;
  }
  return i == last + 1;
}

// CLI11 reads an empty argument as 0 and "-1" as 2^64 - 1 for an unsigned
// option: both are refused here, as NaN and infinity are for any number.
CLI::Validator plain_number(bool is_unsigned) {
  return CLI::Validator(
      [is_unsigned](std::string& text) -> std::string {
        if (text.find_first_not_of(" \t") == std::string::npos) return "an empty argument is not a number";
        const std::size_t first = text.find_first_not_of(" \t");
        if (is_unsigned && text[first] == '-') return fmt::format("must not be negative, got '{}'", cut(text));
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (end != text.c_str() && !std::isfinite(v)) return fmt::format("must be a finite number, got '{}'", cut(text));
        if (!is_decimal(text))
          return fmt::format("must be a decimal number (digits, optional fraction and exponent: 12, -0.5, 1e6), got '{}'",
                             cut(text));
        return "";
      },
      "");
}

}  // namespace

void check_number_options(CLI::App& app) {
  for (CLI::Option* opt : app.get_options()) {
    const std::string type = opt->get_type_name();
    const std::string base = type.substr(0, type.find(':'));
    if (base == "FLOAT" || base == "INT" || base == "UINT") opt->check(plain_number(base == "UINT"));
  }
  for (CLI::App* sub : app.get_subcommands({})) check_number_options(*sub);
}

}  // namespace gpm::cli
