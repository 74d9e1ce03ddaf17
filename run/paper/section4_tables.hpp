// Tables 5-8 and Figures 3-5 of the paper (section 4): GA, PSO and DE
// (calib/global) on J1, J2, J3 with the paper's 12 free parameters
// (x_a^1, y_a^1, x_a^2 fixed), 50 random workspace samples of the Table 5
// mechanism, an equal budget of error-function evaluations per run (the
// paper: 5e7); and the section-4.5 "actual calibration" on the twin: DE on
// J3, 12 parameters, 50 noisy readings on a circle, about 1e6 evaluations.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include <Eigen/Core>

#include "run/paper/paper_table.hpp"

namespace gpm::paper {

struct Section4Settings {
  long budget = 5'000'000;  // evaluations per GA/PSO/DE run (Table 6); the paper's is 5e7
  std::uint64_t seed = 1;   // of every stochastic run
  int parallel_runs = 0;    // comparison runs at once (0 = all cores); results do not depend on it
};

struct Section4Tables {
  Table table5, table6, table7, figure3, figure4, figure5;
};

// (evaluations done, in total) of the comparison, about twice a second.
using EvaluationProgress = std::function<void(long done, long total)>;

// Runs the nine GA/PSO/DE x J1/J2/J3 runs and a DE run with 11 free
// parameters, and builds Tables 5-7 and Figures 3-5. Throws InputError for a
// budget < 1.
Section4Tables section4_tables(const Section4Settings& settings, const EvaluationProgress& progress = {});

// Whether Table 8's printed J3 at the nominal values (2.1517e5) fits its
// printed calibrated values (eq. 43): J3 at the nominal values for exact
// readings of the printed calibrated mechanism at 50 poses on circles.
struct Table8Consistency {
  double radius_lo_mm = 0.0, radius_hi_mm = 0.0;     // circles about `centre`, every pose reachable
  double j3_lo = 0.0, j3_hi = 0.0, j3_median = 0.0;  // over those radii (mm^4)
  int circles_anywhere = 0;                          // reachable circles anywhere (10 mm grid of centres)
  double radius_anywhere_lo_mm = 0.0, radius_anywhere_hi_mm = 0.0;  // their radii
  double j3_anywhere_lo = 0.0;                       // the lowest J3 over them (mm^4)
};

// The comparison above, circles about `centre` (the paper: the workspace
// centre) every 5 mm of radius; well under a second.
Table8Consistency table8_consistency(const Eigen::Vector2d& centre);

// Table 8 on the twin (scenarios/paper_table8_robot.yaml): samples
// simulated, then DE on J3 with 12 free parameters for `evaluations`.
Table table8(long evaluations, std::uint64_t seed);

}  // namespace gpm::paper
