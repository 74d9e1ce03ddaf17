// gpm-render: the renderer behind `gpm render` (gpm execs it with the same
// arguments, "render" included), a separate executable so that only the
// commands that render load OSMesa and libav. Same messages and exit codes as
// gpm (app/cli_main.hpp).
#include "app/cli_main.hpp"
#include "app/commands.hpp"
#include "app/number_options.hpp"

int main(int argc, char** argv) {
  CLI::App app{"gpm: digital twin and auto-calibration toolkit for the GPM2002 planar 3-RRR manipulator"};
  app.require_subcommand(1);
  gpm::cli::add_render(app);
  gpm::cli::check_number_options(app);
  return gpm::cli::run_app(app, argc, argv);
}
