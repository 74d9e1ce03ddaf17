// Angle errors of a motor-side absolute encoder as they appear in the joint
// reading (scenarios/SCHEMA.md, effects), and the latch time of each reading.
//
// The encoder sits on the motor, N = Effects::gear_ratio motor revolutions per
// joint revolution, so an error that repeats k times per MOTOR revolution
// repeats k N times per joint revolution. With r the error-free joint reading
// (rad, r = theta_motor - dth) the error added to the joint reading is
//   e(r) = A_1 sin(N r + phi_1) + sum_h A_h sin(k_h N r + phi_h)   (rad)
// A_1, phi_1: Effects::encoder_cyclic_rad / encoder_phase_rad (eccentricity);
// A_h, phi_h, k_h: Effects::encoder_harmonics (interpolation error). The
// amplitudes are stated as they appear in the joint reading: a motor-side
// error of a arcsec is a / N arcsec there.
// Latch time: encoder i reads the motor angle at t - skew_i - tau,
// tau ~ N(0, jitter_i^2) drawn per reading from the twin's seeded noise source.
#pragma once

#include <array>

#include "models/rng.hpp"

namespace gpm::sim {

struct Effects;

// Harmonics of the encoder error besides the once-per-motor-revolution one.
inline constexpr int kMaxEncoderHarmonics = 4;

// One harmonic of the encoder error per chain (index 0..2 = chain 1..3).
struct EncoderHarmonic {
  int order = 0;                          // k: cycles per motor revolution (0 = unused slot)
  std::array<double, 3> amplitude_rad{};  // A, as seen in the joint reading, rad
  std::array<double, 3> phase_rad{};      // phi (seeded per encoder, see effects_yaml)

  // True if the slot is used and some chain has an amplitude.
  bool on() const { return order > 0 && (amplitude_rad[0] != 0.0 || amplitude_rad[1] != 0.0 || amplitude_rad[2] != 0.0); }
};

// Error e(r) (rad, see the file comment) of encoder i at error-free joint reading r (rad).
double encoder_angle_error(const Effects& fx, int i, double r);

// Latch time offset of one reading of encoder i (s): skew_i + jitter_i x n,
// n ~ N(0, 1) from rng; draws nothing when jitter_i = 0.
double latch_offset_s(const Effects& fx, int i, Rng& rng);

// Draws the encoder and geometry effects of this file per chain from the
// plausible ranges of scenarios/SCHEMA.md: encoder harmonics (orders 2 and 4,
// amplitudes and phases), latch jitter, hub pin offsets, the base plate's
// expansion coefficient and time constant. Reads e.gear_ratio (a data-sheet
// value, not drawn) to state motor-side amplitudes in the joint reading.
// Leaves every other field alone (encoder_cyclic_rad, its phase and the
// warm-up itself belong to the randomized preset; parse_effects re-seeds the
// harmonic phases from the scenario seed).
void draw_encoder_and_geometry(Rng& rng, Effects& e);

}  // namespace gpm::sim
