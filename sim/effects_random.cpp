#include "sim/effects_random.hpp"

#include <algorithm>
#include <cmath>

#include "models/mjcf.hpp"

namespace gpm::sim {

double EffectRange::draw(Rng& rng) const {
  if (log_uniform) return std::exp(rng.uniform(std::log(lo), std::log(hi)));
  return rng.uniform(lo, hi);
}

namespace {

// A value uniformly within a stated tolerance.
double within(Rng& rng, const Stated& s) { return rng.uniform(s.min(), s.max()); }

// The part of the model's damping the effects add: the data sheet states the
// drive's whole viscous friction, the model has kGearboxDamping of it already.
constexpr double kGearboxDamping_Nm_s = MjcfOptions{}.active_damping;

}  // namespace

Effects randomized_effects(Rng& rng, const DataSheet& sheet, const RandomizedRanges& r) {
  Effects e;
  e.gear_ratio = sheet.gear_ratio;
  for (size_t i = 0; i < 3; ++i) {
    e.mjcf.clearance_m[i] = r.clearance_mm.draw(rng) * kMetresPerMm;
    e.mjcf.coulomb_Nm[i] = within(rng, sheet.coulomb_Nm);
    e.mjcf.viscous_Nm_s[i] = std::max(0.0, within(rng, sheet.viscous_Nm_s) - kGearboxDamping_Nm_s);
    e.encoder_cyclic_rad[i] = r.encoder_cyclic_rad.draw(rng);
    e.encoder_skew_s[i] = r.skew_s.draw(rng);
  }
  e.thermal.expansion_per_K = r.expansion_per_K.draw(rng);
  e.thermal.rise_K = r.rise_K.draw(rng);
  e.thermal.time_constant_s = r.time_constant_s.draw(rng);
  draw_drive_train(rng, e);  // the transmission: stiffness bands (with their rotor), backlash, ...
  draw_encoder_and_geometry(rng, e);
  return e;
}

void draw_masses_within(Rng& rng, const DataSheet& sheet, MjcfOptions& mjcf) {
  mjcf.active_link_mass_kg = within(rng, sheet.active_link_mass_kg);
  mjcf.passive_link_mass_kg = within(rng, sheet.passive_link_mass_kg);
  mjcf.ee_mass_kg = within(rng, sheet.end_effector_mass_kg);
  mjcf.armature_kg_m2 = within(rng, sheet.rotor_inertia_kg_m2) * sheet.gear_ratio * sheet.gear_ratio;
}

}  // namespace gpm::sim
