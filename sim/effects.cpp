#include "sim/effects.hpp"

#include <cmath>

namespace gpm::sim {

double ThermalEffect::growth(double t_s) const {
  if (!on()) return 0.0;
  return expansion_per_K * rise_K * (-std::expm1(-t_s / time_constant_s));
}

// s_b(t) = alpha_b rise (1 - exp(-t / tau_b)), alpha_b and tau_b defaulting to the links'.
double ThermalEffect::base_growth(double t_s) const {
  if (!base_own()) return growth(t_s);
  if (!on()) return 0.0;
  const double alpha_b = base_expansion_per_K.value_or(expansion_per_K);
  const double tau_b = base_time_constant_s.value_or(time_constant_s);
  return alpha_b * rise_K * (-std::expm1(-t_s / tau_b));
}

bool Effects::any() const {
  const auto nonzero = [](const std::array<double, 3>& a) { return a[0] != 0.0 || a[1] != 0.0 || a[2] != 0.0; };
  return nonzero(mjcf.compliance_rad_per_Nm) || nonzero(mjcf.clearance_m) || nonzero(mjcf.coulomb_Nm) ||
         nonzero(mjcf.viscous_Nm_s) || thermal.on() || nonzero(encoder_cyclic_rad) ||
         nonzero(encoder_skew_s) || drive.any() || encoder_and_geometry_on();
}

bool Effects::encoder_and_geometry_on() const {
  for (const EncoderHarmonic& h : encoder_harmonics)
    if (h.on()) return true;
  return encoder_jitter_s[0] != 0.0 || encoder_jitter_s[1] != 0.0 || encoder_jitter_s[2] != 0.0 || mjcf.pinned_hub();
}

Effects realistic_effects() {
  Effects e;
  e.mjcf.compliance_rad_per_Nm.fill(1e-4);  // 1e4 N m/rad: 10:1 precision planetary, ~3 N m/arcmin
  e.mjcf.clearance_m.fill(0.005e-3);        // 5 um: deep-groove ball bearing, normal (CN) radial clearance
  e.mjcf.coulomb_Nm.fill(0.3);              // reducer and seal breakaway at the output, ~2 % of rated
  e.mjcf.viscous_Nm_s.fill(0.1);            // reducer churning at the output
  e.thermal = ThermalEffect{23e-6, 3.0, 600.0};  // aluminium, 3 K warm-up, 10 min
  e.encoder_cyclic_rad.fill(2e-5);          // 17-bit absolute encoder, +-4 arcsec accuracy class
  e.encoder_skew_s = {0.0, 50e-6, 100e-6};  // drives latched on a serial bus, 50 us apart
  return e;
}

Geometry thermal_geometry(const Geometry& g0, double s) { return thermal_geometry(g0, s, s); }

// A_i' = c + (A_i - c)(1 + s_base) with c the centroid of A1..A3 (mm);
// la_i' = la_i (1 + s_links), lb_i' = lb_i (1 + s_links).
Geometry thermal_geometry(const Geometry& g0, double s_links, double s_base) {
  Geometry g = g0;
  if (s_links == 0.0 && s_base == 0.0) return g;
  double cx = 0.0, cy = 0.0;
  for (int i = 0; i < kNumChains; ++i) cx += g0[xa(i)] / 3.0, cy += g0[ya(i)] / 3.0;
  for (int i = 0; i < kNumChains; ++i) {
    g[xa(i)] = cx + (g0[xa(i)] - cx) * (1.0 + s_base);
    g[ya(i)] = cy + (g0[ya(i)] - cy) * (1.0 + s_base);
    g[la(i)] = g0[la(i)] * (1.0 + s_links);
    g[lb(i)] = g0[lb(i)] * (1.0 + s_links);
  }
  return g;
}

Geometry thermal_geometry_at(const Geometry& g0, const ThermalEffect& th, double t_s) {
  return thermal_geometry(g0, th.growth(t_s), th.base_growth(t_s));
}

}  // namespace gpm::sim
