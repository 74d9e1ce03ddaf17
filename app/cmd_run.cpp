// gpm run: Simulate, calibrate, compensate and report a scenario.
// Placeholder until Scenario-driven runs (issue 8) lands.
#include "app/commands.hpp"

namespace gpm::cli {

void add_run(CLI::App& app) {
  auto* cmd = app.add_subcommand("run", "Simulate, calibrate, compensate and report a scenario [not available yet]");
  cmd->allow_extras();
  cmd->callback([] { not_available("run", "Scenario-driven runs (issue 8)"); });
}

}  // namespace gpm::cli
