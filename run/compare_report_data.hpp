// The plain data of `gpm compare`'s report (report/compare_report.hpp),
// copied out of a comparison of global methods (calib/global/comparison.hpp).
#pragma once

#include "calib/global/comparison.hpp"
#include "report/compare_report.hpp"

namespace gpm::scenario {

// The report's data of a finished comparison, with the paper's Table 6 beside it.
report::CompareReport compare_report_data(const calib::global::Comparison& c);

}  // namespace gpm::scenario
