// What every toolkit executable (gpm, gpm-render) does around its command
// line: the exit-code policy and the output policy's signal handling.
#pragma once

#include <CLI/CLI.hpp>

namespace gpm::cli {

// Parses argv with app and runs the chosen subcommand. Returns the exit code:
// 0 success, 1 expectations failed / not converged (set_exit), 2 bad input
// (usage, InputError; one line on stderr), 3 a bug (one line asking for a
// report). Before parsing, SIGINT/SIGTERM remove the output temporaries and
// exit 130 (models/output_file.hpp).
int run_app(CLI::App& app, int argc, char** argv);

}  // namespace gpm::cli
