// The reading model (calib/reading_model.hpp).
#include "calib/reading_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "models/errors.hpp"

namespace gpm::calib {

namespace {

void require(bool ok, const std::string& where, const std::string& what) {
  if (!ok) throw InputError(where + what);
}

// Every value of v finite and within [lo, hi].
template <std::size_t N>
bool within(const std::array<double, N>& v, double lo, double hi) {
  for (const double x : v)
    if (!(std::isfinite(x) && x >= lo && x <= hi)) return false;
  return true;
}

}  // namespace

void check_reading_model(const ReadingModel& m, const std::string& where) {
  require(m.encoder_bits >= 0 && m.encoder_bits <= 40, where,
          fmt::format("encoder_bits {} is out of range (0 for an ideal encoder, else 1..40)", m.encoder_bits));
  require(m.noise_rad >= 0.0 && std::isfinite(m.noise_rad), where, "noise_rad must be finite and >= 0");
  require(m.encoder_bits > 0 || m.noise_rad > 0.0, where,
          "an ideal encoder (bits 0) without noise_rad gives zero noise: give bits or noise_rad");
  require(m.load.friction_speed_rad_s >= 0.0 && std::isfinite(m.load.friction_speed_rad_s), where,
          "friction_speed_rad_s must be finite and >= 0");
  for (std::size_t k = 0; k < 3; ++k) {
    const std::size_t i = k + 1;
    require(std::isfinite(m.skew_s[k]) && std::abs(m.skew_s[k]) <= 0.01, where,
            fmt::format("skew_s of encoder {} must be within +-0.01 s", i));
    require(within(std::array{m.compliance_rad_per_Nm[k]}, 0.0, 1.0), where,
            fmt::format("compliance_rad_per_Nm of chain {} must be in 0..1", i));
    require(within(std::array{m.load.coulomb_Nm[k], m.load.viscous_Nm_s[k]}, 0.0, 1e3), where,
            fmt::format("coulomb_Nm and viscous_Nm_s of chain {} must be in 0..1000", i));
    require(within(std::array{m.cyclic_rad[k], m.backlash_rad[k]}, 0.0, 0.01), where,
            fmt::format("cyclic_rad and backlash_rad of joint {} must be in 0..0.01", i));
    require(within(std::array{m.clearance_mm[k]}, 0.0, 2.0), where,
            fmt::format("clearance_mm of chain {} must be in 0..2", i));
  }
  for (const auto& h : m.harmonic) require(within(h, -0.01, 0.01), where, "harmonic coefficients must be in +-0.01 rad");
  for (const double r : m.reducer_home_rad)
    require(std::isnan(r) || std::isfinite(r), where, "reducer_home_rad must be finite (rad) where given");
  require(m.gear_ratio >= 1.0 && std::isfinite(m.gear_ratio), where, "gear_ratio must be finite and >= 1");
  require(m.cogging_periods >= 0.0 && m.cogging_periods <= 1000.0, where, "cogging_periods must be in 0..1000");
  const auto& cogging = m.harmonic[kCoggingHarmonic];
  require(m.cogging_periods > 0.0 || std::ranges::all_of(cogging, [](double v) { return v == 0.0; }), where,
          "the cogging harmonic (the fourth list of harmonic_rad) needs cogging_periods > 0");
}

std::array<double, 3> pin_clearance_mm(const ReadingModel& m) {
  return {0.5 * m.clearance_mm[0], 0.5 * m.clearance_mm[1], 0.5 * m.clearance_mm[2]};
}

double encoder_step_rad(int bits) { return bits > 0 ? 2.0 * std::numbers::pi / std::ldexp(1.0, bits) : 0.0; }

double reading_sigma(double step_rad, double noise_rad, double n_avg) {
  return std::sqrt(noise_rad * noise_rad / n_avg + step_rad * step_rad / 12.0);
}

double reading_sigma(const ReadingModel& m) { return reading_sigma(encoder_step_rad(m.encoder_bits), m.noise_rad); }

double harmonic_angle(int o, double theta_m, double gear_ratio, double cogging_periods) {
  if (o == kCoggingHarmonic) return cogging_periods * gear_ratio * theta_m;
  return o == 0 ? theta_m : o * gear_ratio * theta_m;
}

double link_angle(const ReadingModel& m, int i, double theta_m, double omega, double tau_t, double flank) {
  const auto k = static_cast<std::size_t>(i);
  double theta = theta_m + (m.skew_s[k] * omega - m.compliance_rad_per_Nm[k] * tau_t);
  if (m.backlash_rad[k] != 0.0) theta -= m.backlash_rad[k] * flank;
  for (int o = 0; o < kHarmonicOrders; ++o) {
    const auto& h = m.harmonic[static_cast<std::size_t>(o)];
    if (h[k] == 0.0 && h[k + 3] == 0.0) continue;
    const double a = harmonic_angle(o, theta_m, m.gear_ratio, m.cogging_periods);
    theta -= h[k] * std::sin(a) + h[k + 3] * std::cos(a);
    if (referenced_at_home(o) && std::isfinite(m.reducer_home_rad[k])) {  // referenced to 0 at home
      const double a_home = harmonic_angle(o, m.reducer_home_rad[k], m.gear_ratio, m.cogging_periods);
      theta += h[k] * std::sin(a_home) + h[k + 3] * std::cos(a_home);
    }
  }
  return theta;
}

double reading_at(const ReadingModel& m, int i, double theta) {
  double r = theta;
  for (int step = 0; step < 4; ++step) r += theta - link_angle(m, i, r, 0.0, 0.0, 0.0);
  return r;
}

}  // namespace gpm::calib
