// The plain data of the monitor's report section (report/monitor_report.hpp),
// copied out of a monitor run (run/monitor_run.hpp).
#pragma once

#include "report/monitor_report.hpp"
#include "run/monitor_run.hpp"

namespace gpm::scenario {

// The report's data of a finished monitor run.
report::MonitorReport monitor_report_data(const MonitorOutcome& o);

}  // namespace gpm::scenario
