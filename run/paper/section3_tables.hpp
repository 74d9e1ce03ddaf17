// Tables 2, 3 and 4 of the paper (section 3.3): local calibration (Ceres LM in
// place of Matlab's fmincon) from exact encoder readings, as the paper did it:
// Table 2 on the nominal mechanism with offsets 1.0 (its printed initial
// estimates come from that mechanism), Tables 3 and 4 on the section-3
// "actual" values (calib/paper_values.hpp); initial offsets from the readings
// at the rough home guess (210, 245) (section 3.2 step 3), J1/J2 with 3 and 9
// samples, J1/J2/J3 with 21 samples, J3 with 12 and 11 free parameters from
// 31 samples.
#pragma once

#include <Eigen/Core>

#include "models/robot.hpp"
#include "run/paper/paper_table.hpp"

namespace gpm::paper {

// Where the paper's operator believed home was when reading the encoders
// for the initial offsets (section 3.3 A).
inline const Eigen::Vector2d kRoughHome{210.0, 245.0};

// Initial geometry of the section-3.2 procedure: model with its offsets from
// the readings of actual standing at `at`, taken as if it stood at model.home
// (eq. 35 solved for dth).
Geometry reference_start(const Robot& model, const Robot& actual, const Eigen::Vector2d& at);

// Table 2: offsets only; J1 and J2; 3 and 9 samples; the nominal mechanism
// with offsets 1.0, and the initial estimates section 3's actual values would give.
Table table2();
// Table 3: offsets and the six links from 21 samples; J1, J2, J3.
Table table3();
// Table 4: 12 parameters (xa1 ya1 ya2 fixed; rank 11) and 11 (xa2 fixed too) from 31 samples; J3.
Table table4();

// The point of Table 4's 12-parameter family (x_a^1, y_a^1, y_a^2 fixed; rank
// 11 of 12) turned by `rotation` (rad) about A1: actual's bases rotated and
// scaled about A1 so that y_a^2 keeps its value, links scaled alike, every
// offset plus `rotation`. It fits every exact reading of actual.
Geometry similarity_point(const Geometry& actual, double rotation);

// Where Table 4's printed kmrmse 3.3521 (printed in the initial-estimation
// column) belongs: the kmrmse (eq. 40) of the printed initial estimate and of
// the family point at the printed 12-parameter offsets, on exact samples of
// the section-3 actual mechanism; this run's 31 samples, and 31 samples in
// discs of several radii about home.
struct KmrmsePlacement {
  double rotation = 0.0;                             // printed 12-parameter offset minus the actual 1.0 (rad)
  double initial_mm = 0.0, family_mm = 0.0;          // this run's samples (disc of 100 mm about home)
  double radius_lo_mm = 0.0, radius_hi_mm = 0.0;     // the discs of the sweep
  double initial_lo_mm = 0.0, initial_hi_mm = 0.0;   // the initial estimate over the sweep
  double family_lo_mm = 0.0, family_hi_mm = 0.0;     // the family point over the sweep
};

// The comparison above (a fraction of a second).
KmrmsePlacement table4_kmrmse_placement();

}  // namespace gpm::paper
