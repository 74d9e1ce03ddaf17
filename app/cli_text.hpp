// Wording of the terminal output of gpm (issue 35.5): units in UTF-8 (µm, χ²)
// when stdout is a terminal whose locale is UTF-8, ASCII otherwise; counts
// with the right plural; long user text cut in error messages. Machine-read
// outputs (--json, CSV, summary.json) never use these.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace gpm::cli {

// True when a locale setting says UTF-8: the first non-empty of LC_ALL,
// LC_CTYPE, LANG (as the C library chooses) contains "UTF-8" or "utf8", any case.
bool locale_is_utf8(const char* lc_all, const char* lc_ctype, const char* lang);

// True when stdout is a terminal and the environment's locale is UTF-8
// (decided once per process).
bool terminal_utf8();

// "µm" on a UTF-8 terminal, else "um".
const char* um();
// "χ²" on a UTF-8 terminal, else "chi2".
const char* chi2();

// ", X µm of it the error once per joint revolution the readings cannot tell
// from the geometry": the share carried_um of a stated positioning 1-sigma
// (gpm run's and gpm calibrate's lines); empty when it is 0.
std::string carried_share(double carried_um);

// Text of the libraries (notes, the model test's line, the monitor's
// learning and explanations, written in ASCII) as this terminal shows it:
// units as symbols (report::unit_symbols: µm, µrad, χ²) on a UTF-8
// terminal, as written otherwise.
std::string terminal_text(const std::string& text);

// "1 alarm", "2 alarms", "0 alarms" (plural: noun + "s" unless given).
std::string count_of(std::size_t n, const std::string& noun, const std::string& plural = "");

// text itself when it has at most max characters, else its first max
// characters and "…" (a 300-digit argument is not echoed whole).
std::string cut(const std::string& text, std::size_t max = 40);

// Edit distance between a and b (insertions, deletions, substitutions).
std::size_t edit_distance(const std::string& a, const std::string& b);

// The names close to word (for "did you mean"): within 2 edits (1 for words
// of up to 3 characters), or starting with it; nearest first.
std::vector<std::string> close_names(const std::string& word, const std::vector<std::string>& names);

}  // namespace gpm::cli
