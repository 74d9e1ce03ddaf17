// Physical effects of a real GPM2002 that the ideal twin leaves out
// (scenarios/SCHEMA.md, section effects). All are off by default, and off
// means the ideal twin exactly. Where each effect lives:
//   transmission compliance, passive clearance, Coulomb and viscous friction:
//     in the MuJoCo model (models/mjcf.hpp MjcfEffects);
//   thermal growth: the model's geometry edited at run time (sim/twin.cpp);
//   once-per-revolution error and latch skew: the encoder model;
//   harmonics per motor revolution and latch jitter: sim/encoder_error.hpp.
#pragma once

#include <array>
#include <cmath>
#include <optional>

#include "sim/encoder_error.hpp"

#include "models/mjcf.hpp"
#include "models/parameters.hpp"
#include "sim/drive_train.hpp"

namespace gpm::sim {

// First-order temperature rise of the whole mechanism (links and base plate):
// dT(t) = rise_K (1 - exp(-t / time_constant_s)); every link length grows by
// the factor 1 + expansion_per_K dT(t). The base plate (the distances between
// A1..A3) grows the same way unless it has its own coefficient or time
// constant: dT_b(t) = rise_K (1 - exp(-t / tau_b)), factor 1 + alpha_b dT_b(t)
// (e.g. a steel or cast-iron base under aluminium links, warming slower).
struct ThermalEffect {
  double expansion_per_K = 0.0;   // linear expansion coefficient of the links, 1/K
  double rise_K = 0.0;            // final temperature rise, K
  double time_constant_s = 600.0; // first-order time constant, s
  std::optional<double> base_expansion_per_K = std::nullopt;  // alpha_b, 1/K (unset: expansion_per_K)
  std::optional<double> base_time_constant_s = std::nullopt;  // tau_b, s (unset: time_constant_s)

  bool on() const { return rise_K != 0.0 && (expansion_per_K != 0.0 || base_expansion_per_K.value_or(0.0) != 0.0); }
  // True if the base plate grows by a law of its own.
  bool base_own() const { return base_expansion_per_K.has_value() || base_time_constant_s.has_value(); }
  // Relative growth of every link length at time t (0 when off).
  double growth(double t_s) const;
  // Relative growth of the base plate at time t (growth(t) unless base_own()).
  double base_growth(double t_s) const;
};

// Every effect, per chain where it is per chain (index 0..2 = chain 1..3).
struct Effects {
  MjcfEffects mjcf;                        // compliance, clearance, friction (the MuJoCo part)
  ThermalEffect thermal;
  std::array<double, 3> encoder_cyclic_rad{};  // amplitude of the once-per-revolution error
  std::array<double, 3> encoder_phase_rad{};   // its phase (seeded per encoder, see effects_yaml)
  std::array<double, 3> encoder_skew_s{};      // latch time offset (the reading is of t - skew)
  // Motor revolutions per joint revolution: the encoder sits on the motor, so
  // a joint revolution has 2^bits x gear_ratio counts and errors that repeat
  // per motor revolution repeat gear_ratio times per joint revolution.
  // 1 = direct drive (and the ideal twin).
  double gear_ratio = 1.0;
  DriveTrain drive;  // backlash, stiffness bands, TE, friction, torque constant, cogging (sim/drive_train.hpp)
  // Motor-side encoder errors beyond the once-per-revolution one, and latch
  // jitter (sim/encoder_error.hpp; all off by default).
  std::array<EncoderHarmonic, kMaxEncoderHarmonics> encoder_harmonics{};
  std::array<double, 3> encoder_jitter_s{};  // standard deviation of each reading's latch time, s

  // True if anything differs from the ideal twin.
  bool any() const;
  // True if an encoder harmonic, latch jitter or a hub pin offset is on (sim/encoder_error.hpp).
  bool encoder_and_geometry_on() const;
};

// The `realistic` preset: GPM2002-scale values (reasoning in scenarios/SCHEMA.md).
Effects realistic_effects();

// Geometry at relative growth s: links scaled by 1 + s, base joints moved away
// from the centroid of A1..A3 by the same factor; zero offsets unchanged.
Geometry thermal_geometry(const Geometry& g0, double growth);

// Geometry with links scaled by 1 + s_links and the base joints moved away
// from the centroid of A1..A3 by the factor 1 + s_base; zero offsets unchanged.
Geometry thermal_geometry(const Geometry& g0, double s_links, double s_base);

// The thermal growth of th at time t applied to g0 (links and base by their own laws).
Geometry thermal_geometry_at(const Geometry& g0, const ThermalEffect& th, double t_s);

// Encoder angle error of the once-per-revolution term: amplitude sin(angle + phase).
inline double cyclic_error(double amplitude, double phase, double angle) {
  return amplitude != 0.0 ? amplitude * std::sin(angle + phase) : 0.0;
}

}  // namespace gpm::sim
