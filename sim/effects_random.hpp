// The `randomized` effects preset: one robot of the GPM2002 class, every
// effect drawn per chain from its plausible range (scenarios/SCHEMA.md,
// section effects, "randomized": each range with its source). A real robot
// is never the `realistic` preset; a population of these is what a
// procedure is judged on (`gpm study population`).
#pragma once

#include "models/data_sheet.hpp"
#include "models/mjcf.hpp"
#include "models/rng.hpp"
#include "sim/effects.hpp"

namespace gpm::sim {

// Plausible range of one effect: drawn uniformly in [lo, hi], or uniformly in
// log between them (log_uniform: for values known to a factor, lo > 0).
struct EffectRange {
  double lo = 0.0, hi = 0.0;
  bool log_uniform = false;

  // One draw from the range.
  double draw(Rng& rng) const;
};

// The ranges the `randomized` preset draws from (output-side units, as the
// effects keys): the numbers and their sources are in scenarios/SCHEMA.md.
struct RandomizedRanges {
  EffectRange clearance_mm{0.0, 0.020};                  // passive joints' radial play
  EffectRange expansion_per_K{21e-6, 24e-6};             // aluminium alloys
  EffectRange rise_K{0.5, 5.0};                          // warm-up of the machine
  EffectRange time_constant_s{300.0, 1800.0, true};
  EffectRange encoder_cyclic_rad{2.4e-6, 2e-5, true};    // 5 to 40 arcsec at the motor, through 10:1
  EffectRange skew_s{0.0, 200e-6};                       // latch time of each drive on the bus
};

// One robot of the class: every effect drawn per chain from ranges (each
// chain independently), with the drive train (sim/drive_train.hpp) and the
// encoder and geometry effects (sim/encoder_error.hpp) drawn from theirs; the
// drive friction per chain within the data sheet's tolerance, the gear ratio
// the data sheet's. Encoder phases are left for the caller to seed.
Effects randomized_effects(Rng& rng, const DataSheet& sheet = {}, const RandomizedRanges& ranges = {});

// The actual masses and rotor inertia of one robot (the whole robot: the
// model has one value of each), each drawn uniformly within the data sheet's
// tolerance; mjcf's other settings are kept.
void draw_masses_within(Rng& rng, const DataSheet& sheet, MjcfOptions& mjcf);

}  // namespace gpm::sim
