// Particle swarm optimisation as the paper sets it (section 4.2).
#pragma once

#include <cstdint>

#include "calib/global/objective.hpp"

namespace gpm::calib::global {

// Paper section 4.4: N = 100, C1 = C2 = 2, inertia 0.9 falling linearly to
// 0.1 over the budget, half the particles re-initialised after NR = 50
// generations without improvement.
struct PsoSettings {
  int population = 100;
  double c1 = 2.0;
  double c2 = 2.0;
  double w_start = 0.9;
  double w_end = 0.1;
  int stall_generations = 50;
};

// Minimises obj with PSO: V <- w V + C1 R1 (Pbest - X) + C2 R2 (Gbest - X),
// X <- X + V (eq. 45), R1, R2 uniform on [0, 1] per coordinate, w = w_start +
// (w_end - w_start) * evaluations / budget. A particle leaving the box is put
// on its border (paper); velocities are limited to the box width per
// coordinate (the paper gives no limit; without one the swarm explodes at w
// near 0.9). After stall_generations without a better Gbest, half the
// particles (never the one holding Gbest) get new random positions,
// velocities and personal bests. Never exceeds stop.budget evaluations; the
// same seed gives the same run.
RunRecord minimise_pso(const BatchObjective& obj, const PsoSettings& settings,
                       const StopRule& stop, uint64_t seed, const ProgressFn& progress = {});

}  // namespace gpm::calib::global
