// gpm calibrate: Identify kinematic parameters from encoder samples.
// Placeholder until Calibration from encoder data (issue 4) lands.
#include "app/commands.hpp"

namespace gpm::cli {

void add_calibrate(CLI::App& app) {
  auto* cmd = app.add_subcommand("calibrate", "Identify kinematic parameters from encoder samples [not available yet]");
  cmd->allow_extras();
  cmd->callback([] { not_available("calibrate", "Calibration from encoder data (issue 4)"); });
}

}  // namespace gpm::cli
