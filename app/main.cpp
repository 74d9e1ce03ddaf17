// gpm: the command line of the GPM2002 digital twin and calibration toolkit.
// Thin: parses, calls the libraries, prints. Exit codes (docs/CLI.md): 0 success,
// 1 the run worked but failed its expectations, 2 bad input (one line on
// stderr), 3 a bug, 130 interrupted. `gpm render` runs the renderer, a
// separate executable (gpm-render, next to gpm), so that gpm itself loads
// neither OSMesa nor libav.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>

#include <fmt/format.h>
#include <unistd.h>

#include "app/cli_main.hpp"
#include "app/commands.hpp"

namespace {

// Replaces this process by gpm-render with the same arguments; returns only
// on failure (exit 2, the renderer is not installed beside gpm).
int exec_renderer(char** argv) {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  const std::filesystem::path renderer = (ec ? std::filesystem::path(argv[0]) : self).parent_path() / "gpm-render";
  ::execv(renderer.c_str(), argv);
  const int err = errno;
  std::fprintf(stderr, "gpm: error: gpm render: cannot run the renderer %s: %s (install gpm-render next to gpm)\n",
               renderer.c_str(), std::strerror(err));
  return 2;
}

// Lists `render` in gpm's help; never runs (main execs gpm-render first).
void add_render_entry(CLI::App& app) {
  app.add_subcommand("render", gpm::cli::kRenderDescription)->allow_extras()->prefix_command();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 2 && std::strcmp(argv[1], "render") == 0) return exec_renderer(argv);
  CLI::App app{"gpm: digital twin and auto-calibration toolkit for the GPM2002 planar 3-RRR manipulator"};
  gpm::cli::add_commands(app, add_render_entry);
  return gpm::cli::run_app(app, argc, argv);
}
