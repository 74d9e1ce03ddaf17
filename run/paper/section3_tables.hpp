// Tables 2, 3 and 4 of the paper (section 3.3): local calibration (Ceres LM in
// place of Matlab's fmincon) from exact encoder readings generated with the
// section-3 "actual" values (calib/paper_values.hpp), as the paper did it:
// initial offsets from the readings at the rough home guess (210, 245)
// (section 3.2 step 3), J1/J2 with 3 and 9 samples, J1/J2/J3 with 21 samples,
// J3 with 12 and 11 free parameters from 31 samples.
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

// Table 2: offsets only; J1 and J2; 3 and 9 samples.
Table table2();
// Table 3: offsets and the six links from 21 samples; J1, J2, J3.
Table table3();
// Table 4: 12 parameters (xa1 ya1 ya2 fixed; rank 11) and 11 (xa2 fixed too) from 31 samples; J3.
Table table4();

}  // namespace gpm::paper
