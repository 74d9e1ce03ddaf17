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

double quantise_reading(const EncoderModel& model, double angle) {
  const double a = wrap_2pi(angle);
  if (model.bits <= 0) return a;
  const long long counts = 1LL << model.bits;
  long long c = std::llround(a / model.count_rad());
  if (c >= counts) c -= counts;
  return static_cast<double>(c) * model.count_rad();
}

double encoder_reading(const EncoderModel& model, EncoderNoise& noise, double theta_a, double dth) {
  double a = theta_a - dth;  // eq. 35
  if (model.noise_rad > 0.0) a += model.noise_rad * noise.rng.normal();
  return quantise_reading(model, a);
}

}  // namespace gpm::sim
