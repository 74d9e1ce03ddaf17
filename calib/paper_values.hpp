// Parameter values of the paper's simulation experiments (reference/paper.md
// sections 3.3 and 4.4), with the corrections of docs/EQUATIONS.md applied, for tests, studies and
// benchmarks. Millimetres and radians.
#pragma once

#include "calib/problem.hpp"
#include "models/parameters.hpp"
#include "models/samples.hpp"

namespace gpm::calib {

// Section 3.3 "actual" values (Tables 2-4): offsets 1.0 rad; la = 244.1,
// 244.2, 244.5 (docs/EQUATIONS.md: 243.5 is a misprint in section 3), lb = 243.8, 244.2,
// 244.2; A2 = (433.04, 0), A3 = (433.05, 499.96); A1 nominal.
Geometry section3_actual();

// Table 5 "actual" values (section 4.4): A2 = (433, 0.3), A3 = (433.5, 499.4),
// la = 244.1, 244.2, 243.5, lb = 243.8, 244.2, 244.6, offsets 0.01, -0.01, 0.01.
Geometry table5_actual();

// Section 4.4's free set: xa1, ya1, xa2 fixed, the other 12 free (rank 11:
// the similarity family remains, docs/EQUATIONS.md).
FreeMask paper_free_mask();

// The calibration problem of readings s for the Table 5 mechanism: free
// parameters start at the GPM2002 nominal values, fixed ones at their actual
// (true) values (fixing a coordinate at a wrong value fits a similar
// mechanism instead).
Problem table5_problem(const Samples& s, const FreeMask& free);

}  // namespace gpm::calib
