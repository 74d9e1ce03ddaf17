// DIR/summary.json of `gpm run`: the machine-readable summary (keys fixed):
// verdict, robot_time_s, accuracy.{nominal,calibrated,actual}.{static_rms_um,
// static_max_um,path_rms_um}, parameters.<name>.{actual,estimated,std,crb},
// model_test.{chi2,dof,p_value}.
#pragma once

#include <string>

namespace gpm::scenario {

struct RunOutcome;

// The JSON text of a finished run (one document, 2-space indented).
std::string summary_json(const RunOutcome& outcome);

}  // namespace gpm::scenario
