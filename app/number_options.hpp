// Numbers on the command line (issue 36.8, 36.12): one validator for the
// documented range of a flag (models/bounds.hpp, docs/CLI.md "Limits") and one
// check every number option gets (no empty text, no NaN or infinity, no minus
// sign on an unsigned one), so that a refusal is one line naming the flag,
// the value and the valid range (exit 2), before any work.
#pragma once

#include <CLI/CLI.hpp>

#include "models/bounds.hpp"

namespace gpm::cli {

// Validator: the text is a number within b; a whole bound's text is rewritten
// in plain decimal digits (1e6 -> 1000000) for CLI11's integer conversion, so
// add it with Option::transform (CLI11's check() may not rewrite).
CLI::Validator number_in(const Bound& b);

// Adds the check above (empty text, non-finite, negative unsigned) to every
// number option of app and of its subcommands, positional ones included.
void check_number_options(CLI::App& app);

}  // namespace gpm::cli
