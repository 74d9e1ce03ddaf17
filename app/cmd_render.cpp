// gpm render: Render an off-screen MP4 video of a scenario's motion.
// Placeholder until Off-screen rendering (issue 6) lands.
#include "app/commands.hpp"

namespace gpm::cli {

void add_render(CLI::App& app) {
  auto* cmd = app.add_subcommand("render", "Render an off-screen MP4 video of a scenario's motion [not available yet]");
  cmd->allow_extras();
  cmd->callback([] { not_available("render", "Off-screen rendering (issue 6)"); });
}

}  // namespace gpm::cli
