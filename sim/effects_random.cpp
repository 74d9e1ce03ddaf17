#include "sim/effects_random.hpp"

#include <cmath>

#include "models/mjcf.hpp"

namespace gpm::sim {

double EffectRange::draw(Rng& rng) const {
  if (log_uniform) return std::exp(rng.uniform(std::log(lo), std::log(hi)));
  return rng.uniform(lo, hi);
}

Effects randomized_effects(Rng& rng, const RandomizedRanges& r) {
  Effects e;
  for (size_t i = 0; i < 3; ++i) {
    e.mjcf.compliance_rad_per_Nm[i] = 1.0 / r.stiffness_Nm_per_rad.draw(rng);
    e.mjcf.clearance_m[i] = r.clearance_mm.draw(rng) * kMetresPerMm;
    e.mjcf.coulomb_Nm[i] = r.coulomb_Nm.draw(rng);
    e.mjcf.viscous_Nm_s[i] = r.viscous_Nm_s.draw(rng);
    e.encoder_cyclic_rad[i] = r.encoder_cyclic_rad.draw(rng);
    e.encoder_skew_s[i] = r.skew_s.draw(rng);
  }
  e.thermal.expansion_per_K = r.expansion_per_K.draw(rng);
  e.thermal.rise_K = r.rise_K.draw(rng);
  e.thermal.time_constant_s = r.time_constant_s.draw(rng);
  e.gear_ratio = r.gear_ratio;
  return e;
}

}  // namespace gpm::sim
