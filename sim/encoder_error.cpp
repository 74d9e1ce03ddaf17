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

// Plausible ranges (scenarios/SCHEMA.md, effects; motor-side amplitudes in arcsec).
namespace {
constexpr double kArcsec = std::numbers::pi / (180.0 * 3600.0);
constexpr int kDrawnOrders[2] = {2, 4};             // interpolation error per motor revolution
constexpr double kHarmonicArcsec[2][2] = {{1.0, 6.0}, {0.5, 3.0}};
constexpr double kJitter_s[2] = {0.05e-6, 2e-6};     // synchronised drive bus latch
constexpr double kBaseExpansion[2] = {10e-6, 13e-6}; // cast iron to steel, 1/K
constexpr double kBaseTau_s[2] = {1800.0, 7200.0};   // a heavy base plate warming slower
constexpr double kHubPin_m = 20e-6;                  // largest hub pin offset (bore position tolerance)
}  // namespace

// A motor-side amplitude a (arcsec) reads as a / N in the joint reading.
void draw_encoder_and_geometry(Rng& rng, Effects& e) {
  const double to_joint = kArcsec / e.gear_ratio;
  for (size_t k = 0; k < 3; ++k) e.encoder_jitter_s[k] = rng.uniform(kJitter_s[0], kJitter_s[1]);
  for (size_t h = 0; h < 2; ++h) {
    EncoderHarmonic& eh = e.encoder_harmonics[h];
    eh.order = kDrawnOrders[h];
    for (size_t k = 0; k < 3; ++k) {
      eh.amplitude_rad[k] = rng.uniform(kHarmonicArcsec[h][0], kHarmonicArcsec[h][1]) * to_joint;
      eh.phase_rad[k] = rng.uniform(0.0, 2.0 * std::numbers::pi);
    }
  }
  for (auto& p : e.mjcf.hub_pin_m) {  // |p| uniform in [0, 20 um], direction uniform
    const double r = rng.uniform(0.0, kHubPin_m), a = rng.uniform(0.0, 2.0 * std::numbers::pi);
    p = {r * std::cos(a), r * std::sin(a)};
  }
  e.thermal.base_expansion_per_K = rng.uniform(kBaseExpansion[0], kBaseExpansion[1]);
  e.thermal.base_time_constant_s = rng.uniform(kBaseTau_s[0], kBaseTau_s[1]);
}

}  // namespace gpm::sim
