// Where a sampling session takes its poses: a poses file (an explicit list and
// optional sampling settings) or a scenario's sampling plan (sim/scenario.hpp).
//
//   poses: [[236.5, 260], [196.5, 240]]     # mm
//   sampling:                               # optional, defaults of sim/sampling.hpp
//     move_speed_mm_s: 100
//     settle: {velocity_rad_s: 0.001, hold_s: 0.2, timeout_s: 3}
//     average_s: 0.1
#pragma once

#include <string>

#include "hw/procedures/sampling_session.hpp"
#include "hw/safety_limits.hpp"
#include "sim/sampling.hpp"

namespace gpm::hw {

// Sampling settings are bounded where they are parsed (sim/scenario.cpp,
// ranges in scenarios/SCHEMA.md): both plans below go through that parser.

// Loads a poses file (its poses and settings go through the scenario schema's
// sampling parser, pattern list); throws InputError naming the file, line and
// key path, or a setting outside its range.
SessionPlan load_poses_plan(const std::string& path);

// The poses and sampling settings of a scenario's sampling plan (settings
// bounded as above).
SessionPlan plan_from_scenario(const std::string& path);

}  // namespace gpm::hw
