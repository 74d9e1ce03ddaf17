// The report of a `gpm run`: before/after accuracy first, then the
// parameter table (actual, nominal, estimated, 1-sigma, error, bound), the
// diagnostics, the expectations, and figures.
#pragma once

#include "scenarios/report_document.hpp"

namespace gpm::scenario {

struct RunOutcome;

// Builds the report of a finished run.
report::ReportDocument build_report(const RunOutcome& outcome);

}  // namespace gpm::scenario
