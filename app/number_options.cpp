// Numbers on the command line (app/number_options.hpp).
#include "app/number_options.hpp"

#include <charconv>
#include <cmath>
#include <string>

#include <fmt/format.h>

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
          return why.rfind(": ", 0) == 0 ? why.substr(2) : why;
        }
        if (b.whole) text = fmt::format("{:.0f}", v);
        return "";
      },
      describe(b));
}

namespace {

// CLI11 reads an empty argument as 0 and "-1" as 2^64 - 1 for an unsigned
// option: both are refused here, as NaN and infinity are for any number.
CLI::Validator plain_number(bool is_unsigned) {
  return CLI::Validator(
      [is_unsigned](std::string& text) -> std::string {
        if (text.find_first_not_of(" \t") == std::string::npos) return "an empty argument is not a number";
        const std::size_t first = text.find_first_not_of(" \t");
        if (is_unsigned && text[first] == '-') return fmt::format("must not be negative, got '{}'", text);
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (end != text.c_str() && !std::isfinite(v)) return fmt::format("must be a finite number, got '{}'", text);
        return "";  // text that is not a number at all: CLI11's own message
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
