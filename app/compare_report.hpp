// The report of `gpm compare` (paper section 4.4): the Markdown table6.md and
// the convergence figures, from the numbers of calib/global/comparison.hpp.
#pragma once

#include <string>

#include "calib/global/comparison.hpp"

namespace gpm::cli {

// Markdown report: settings, a Table 6 (best J per algorithm and cost, paper
// values beside), the identifiability diagnosis, parameter errors of every
// run against Table 5, the spread across seeds and a verdict.
std::string compare_markdown(const calib::global::Comparison& c);

// SVG figure of log10(J) against evaluations for one cost (Figs. 3-5).
std::string compare_svg(const calib::global::Comparison& c, calib::Cost cost);

}  // namespace gpm::cli
