#include "sim/encoder_error.hpp"

#include <cmath>
#include <numbers>

#include "sim/effects.hpp"

namespace gpm::sim {

// e(r) = A_1 sin(N r + phi_1) + sum_h A_h sin(k_h N r + phi_h); at N = 1 and
// no harmonics exactly cyclic_error(A_1, phi_1, r) (1.0 r is r to the bit).
double encoder_angle_error(const Effects& fx, int i, double r) {
  const size_t k = static_cast<size_t>(i);
  const double motor = fx.gear_ratio * r;  // N r: the motor's turn from the reading's zero, rad
  double e = cyclic_error(fx.encoder_cyclic_rad[k], fx.encoder_phase_rad[k], motor);
  for (const EncoderHarmonic& h : fx.encoder_harmonics)
    if (h.order > 0 && h.amplitude_rad[k] != 0.0) e += h.amplitude_rad[k] * std::sin(h.order * motor + h.phase_rad[k]);
  return e;
}

// dt = skew_i + sigma_i n, n ~ N(0, 1) (s).
double latch_offset_s(const Effects& fx, int i, Rng& rng) {
  const size_t k = static_cast<size_t>(i);
  double dt = fx.encoder_skew_s[k];
  if (fx.encoder_jitter_s[k] > 0.0) dt += fx.encoder_jitter_s[k] * rng.normal();
  return dt;
}

}  // namespace gpm::sim
