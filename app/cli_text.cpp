// Wording of the terminal output (app/cli_text.hpp).
#include "app/cli_text.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <utility>

#include <fmt/format.h>
#include <unistd.h>

#include "report/report_document.hpp"

namespace gpm::cli {

// Edit distance between a and b (insertions, deletions, substitutions).
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

std::vector<std::string> close_names(const std::string& word, const std::vector<std::string>& names) {
  std::vector<std::pair<std::size_t, std::string>> near;
  for (const std::string& n : names) {
    const std::size_t d = edit_distance(word, n);
    const bool prefix = word.size() >= 2 && n.rfind(word, 0) == 0;
    if (d <= (word.size() <= 3 ? 1u : 2u) || prefix) near.emplace_back(prefix ? 0 : d, n);
  }
  std::stable_sort(near.begin(), near.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<std::string> out;
  for (const auto& [d, n] : near) out.push_back(n);
  return out;
}


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

std::string terminal_text(const std::string& text) { return terminal_utf8() ? report::unit_symbols(text) : text; }

std::string carried_share(double carried_um) {
  if (!(carried_um > 0.0)) return {};
  return fmt::format(", {:.2f} {} of it the error once per joint revolution the readings cannot tell from the geometry",
                     carried_um, um());
}

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
