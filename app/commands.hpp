// Subcommands of the `gpm` command line (docs/FORMATS.md). Each file app/cmd_*.cpp
// registers one subcommand; the callbacks throw gpm::InputError for bad input
// (exit 2) and return the exit code through gpm::cli::set_exit().
#pragma once

#include <functional>
#include <string>

#include <CLI/CLI.hpp>

namespace gpm::cli {

// Records the exit code a subcommand wants (0 success, 1 failed expectations);
// app/cli_main.cpp.
void set_exit(int code);
int exit_code();

// Path of the nominal GPM2002 robot file shipped with the sources.
std::string default_model_path();

void add_kin(CLI::App& app);
void add_simulate(CLI::App& app);
void add_calibrate(CLI::App& app);
void add_run(CLI::App& app);
void add_render(CLI::App& app);  // in gpm-render (app/render_main.cpp) only
inline constexpr const char* kRenderDescription =
    "Render an off-screen MP4 video (and PNG frames) of a scenario's motion; a gpm run scenario as its story "
    "(an opening card, the nominal controller, the sampling, the calibrated controller, a closing card with the "
    "before and after errors)";
void add_compare(CLI::App& app);
void add_study(CLI::App& app);
void add_design(CLI::App& app);
void add_sample(CLI::App& app);
void add_zero(CLI::App& app);
void add_monitor(CLI::App& app);
void add_paper(CLI::App& app);
// gpm help [TOPIC]: the installed documents and scenario library (app/cmd_help.cpp).
void add_help(CLI::App& app);

// Registers every subcommand of gpm on app (with the version flag), in the
// order of `gpm --help`; render through add_render_command (gpm registers an
// entry that execs gpm-render, the fuzz target the real one).
void add_commands(CLI::App& app, const std::function<void(CLI::App&)>& add_render_command);

// Throws InputError "gpm NAME: not available yet (...)": a subcommand whose
// issue has not landed.
[[noreturn]] void not_available(const std::string& name, const std::string& issue);

}  // namespace gpm::cli
