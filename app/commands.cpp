// The subcommands of gpm in the order of `gpm --help` (app/commands.hpp).
#include "app/commands.hpp"

#include "app/number_options.hpp"

namespace gpm::cli {

void add_commands(CLI::App& app, const std::function<void(CLI::App&)>& add_render_command) {
  app.require_subcommand(1);
  app.set_version_flag("--version", "gpm 0.1.0");
  add_kin(app);
  add_simulate(app);
  add_calibrate(app);
  add_run(app);
  add_render_command(app);
  add_compare(app);
  add_study(app);
  add_design(app);
  add_sample(app);
  add_zero(app);
  add_monitor(app);
  add_paper(app);
  add_help(app);
  check_number_options(app);  // every number option: no empty text, NaN, infinity (issue 36.12)
}

}  // namespace gpm::cli
