// Wording of the terminal output (app/cli_text.hpp).
#include "app/cli_text.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>

#include <fmt/format.h>
#include <unistd.h>

namespace gpm::cli {

bool locale_is_utf8(const char* lc_all, const char* lc_ctype, const char* lang) {
  const char* chosen = nullptr;
  for (const char* v : {lc_all, lc_ctype, lang})
    if (v && *v) {
      chosen = v;
      break;
    }
  if (!chosen) return false;
  std::string s(chosen);
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s.find("utf-8") != std::string::npos || s.find("utf8") != std::string::npos;
}

bool terminal_utf8() {
  static const bool yes = ::isatty(STDOUT_FILENO) != 0 &&
                          locale_is_utf8(std::getenv("LC_ALL"), std::getenv("LC_CTYPE"), std::getenv("LANG"));
  return yes;
}

const char* um() { return terminal_utf8() ? "\u00b5m" : "um"; }

const char* chi2() { return terminal_utf8() ? "\u03c7\u00b2" : "chi2"; }

std::string count_of(std::size_t n, const std::string& noun, const std::string& plural) {
  return fmt::format("{} {}", n, n == 1 ? noun : (plural.empty() ? noun + "s" : plural));
}

std::string cut(const std::string& text, std::size_t max) {
  if (text.size() <= max) return text;
  std::size_t end = max;
  while (end > 0 && (static_cast<unsigned char>(text[end]) & 0xC0) == 0x80) --end;  // not inside a UTF-8 character
  return text.substr(0, end) + "\u2026";
}

}  // namespace gpm::cli
