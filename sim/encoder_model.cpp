#include "sim/encoder_model.hpp"

#include <cmath>
#include <numbers>

#include "models/kinematics.hpp"

namespace gpm::sim {
namespace {
constexpr double kTwoPi = 2.0 * std::numbers::pi;
}  // namespace

double EncoderModel::count_rad() const {
  return bits > 0 ? kTwoPi / std::ldexp(1.0, bits) : 0.0;
}

double quantise_reading(const EncoderModel& model, double angle) { return quantise_reading(model, angle, 1.0); }

// n = 2^bits N counts per joint revolution, q = 2 pi / n (rad);
// reading = q round(a / q) with a = wrap(angle), the top count n wrapping to
// 0. A whole n (a whole ratio) keeps every reading on the count grid; a
// fractional ratio wraps the multi-turn count, so the reading after the wrap
// is (round(a / q) - n) q. At N = 1, q is count_rad() to the bit.
double quantise_reading(const EncoderModel& model, double angle, double gear_ratio) {
  const double a = wrap_2pi(angle);
  if (model.bits <= 0) return a;
  const double counts = std::ldexp(gear_ratio, model.bits);
  const double q = kTwoPi / counts;
  double c = std::round(a / q);
  if (c >= counts) c -= counts;
  return c * q;
}

double encoder_reading(const EncoderModel& model, EncoderNoise& noise, double theta_a, double dth, double gear_ratio) {
  double a = theta_a - dth;  // eq. 35
  if (model.noise_rad > 0.0) a += model.noise_rad * noise.rng.normal();
  return quantise_reading(model, a, gear_ratio);
}

}  // namespace gpm::sim
