// Binary-coded genetic algorithm as the paper sets it (section 4.1).
#pragma once

#include <cstdint>

#include "calib/global/objective.hpp"

namespace gpm::calib::global {

// Paper section 4.4: N = 100, p = 1e-4, PCrossover = 0.85, PMutation = 0.15,
// tournament of 4, half re-initialised after NR = 50 generations without
// improvement.
struct GaSettings {
  int population = 100;
  double precision = 1e-4;  // p: bits per parameter L = ceil(log2((max - min) / p))
  double p_crossover = 0.85;
  double p_mutation = 0.15;
  int tournament = 4;
  int stall_generations = 50;
};

// Bits of the binary string for one parameter with box width `width`:
// L = ceil(log2(width / precision)), at least 1 and at most 52.
int ga_bits(double width, double precision);

// Minimises obj with a GA: each parameter a binary string of ga_bits() bits
// decoded as min + integer * (max - min) / (2^L - 1); the individual is their
// concatenation. Each generation keeps the best individual unchanged (slot 0)
// and fills the other N - 1 slots with tournament winners (best of 4 drawn
// with replacement); consecutive pairs cross with probability PCrossover at
// one random cut of the whole string; each individual gets two random bits
// flipped with probability PMutation. Only new or changed individuals are
// evaluated. After stall_generations without a better best, a random half
// (never the best) is re-initialised. Never exceeds stop.budget evaluations;
// the same seed gives the same run.
RunRecord minimise_ga(const BatchObjective& obj, const GaSettings& settings, const StopRule& stop,
                      uint64_t seed, const ProgressFn& progress = {});

}  // namespace gpm::calib::global
