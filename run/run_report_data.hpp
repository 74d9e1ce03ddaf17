// The plain data of a run's report (report/run_report.hpp): what the report
// library needs from calib/ and sim/, copied out of a RunOutcome.
#pragma once

#include "report/run_report.hpp"

namespace gpm::scenario {

struct RunOutcome;

// The report's data of a finished run (tracking error every 10th log row).
report::RunReport run_report_data(const RunOutcome& outcome);

}  // namespace gpm::scenario
