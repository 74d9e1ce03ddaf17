// gpm simulate: Simulate a scenario on the MuJoCo twin: DIR/samples.csv, trajectory.csv, actual.yaml, model.xml.
// Placeholder until Digital twin (issue 3) lands.
#include "app/commands.hpp"

namespace gpm::cli {

void add_simulate(CLI::App& app) {
  auto* cmd = app.add_subcommand("simulate", "Simulate a scenario on the MuJoCo twin: DIR/samples.csv, trajectory.csv, actual.yaml, model.xml [not available yet]");
  cmd->allow_extras();
  cmd->callback([] { not_available("simulate", "Digital twin (issue 3)"); });
}

}  // namespace gpm::cli
