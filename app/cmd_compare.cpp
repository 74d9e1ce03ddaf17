// gpm compare: equal-budget comparison of GA, PSO and DE on J1, J2, J3.
// Placeholder until Global calibration (issue 5) lands.
#include "app/commands.hpp"

namespace gpm::cli {

void add_compare(CLI::App& app) {
  auto* cmd = app.add_subcommand("compare", "Compare GA, PSO and DE on J1, J2, J3 at equal budget [not available yet]");
  cmd->allow_extras();
  cmd->callback([] { not_available("compare", "Global calibration (issue 5)"); });
}

}  // namespace gpm::cli
