#include "sim/effects_yaml.hpp"

#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "models/errors.hpp"
#include "models/rng.hpp"
#include "models/yaml_util.hpp"
#include "sim/effects_random.hpp"
#include "sim/scenario.hpp"

namespace gpm::sim {
namespace {

struct Range {
  double lo, hi;
  const char* what;  // valid values, for the message
};

double bounded(const YAML::Node& n, const std::string& file, const std::string& key, const Range& r) {
  const double v = yaml_number(n, file, key);
  if (v < r.lo || v > r.hi)
    throw InputError(yaml_where(file, n, key) + fmt::format("{} is out of range (valid: {})", v, r.what));
  return v;
}

constexpr std::string_view kPerChain = "a number or a list of three (one per chain)";

// A scalar (all three chains) or a list of three, each in range; scale converts units.
std::array<double, 3> per_chain(const YAML::Node& n, const std::string& file, const std::string& key,
                                const Range& r, double scale = 1.0) {
  return yaml_number_or_three(n, file, key, kPerChain,
                              [&](const YAML::Node& v, const std::string& k) { return scale * bounded(v, file, k, r); });
}

// A preset by name; `randomized` draws one robot of the class from the
// scenario seed (stream 6), so a seed names one robot.
Effects preset(const YAML::Node& n, const std::string& file, const std::string& key, std::uint64_t seed,
               const DataSheet& sheet) {
  const std::string name = yaml_string(n, file, key);
  if (name == "ideal") return Effects{};
  if (name == "realistic") return realistic_effects();
  if (name == "randomized") {
    Rng rng(derive_seed(seed, Stream::kRandomizedEffects));
    return randomized_effects(rng, sheet);
  }
  throw InputError(yaml_where(file, n, key) +
                   fmt::format("'{}' is not a preset (valid: ideal, realistic, randomized)", name));
}

// --- Drive train (sim/drive_train.hpp) ---------------------------------------

// Bands of N numbers: a list of N (all chains) or a list of three lists of N.
template <size_t N>
std::array<std::array<double, N>, 3> per_chain_bands(const YAML::Node& n, const std::string& file,
                                                     const std::string& key, const Range& r, const char* what) {
  const auto row = [&](const YAML::Node& l, const std::string& k) {
    if (!l.IsSequence() || l.size() != N) throw InputError(yaml_where(file, l, k) + fmt::format("expected {}", what));
    std::array<double, N> a{};
    for (size_t j = 0; j < N; ++j) a[j] = bounded(l[j], file, fmt::format("{}[{}]", k, j), r);
    return a;
  };
  const std::string both = fmt::format("{} (all chains) or a list of three such lists", what);
  if (n.IsSequence() && n.size() == 3 && n[0].IsSequence()) {
    std::array<std::array<double, N>, 3> a{};
    for (size_t i = 0; i < 3; ++i) a[i] = row(n[i], fmt::format("{}[{}]", key, i));
    return a;
  }
  if (!n.IsSequence() || n.size() != N) throw InputError(yaml_where(file, n, key) + "expected " + both);
  const auto a = row(n, key);
  return {a, a, a};
}

// Sets field of every chain from three values.
void set_chains(DriveTrain& dt, double DriveChain::*field, const std::array<double, 3>& v) {
  for (size_t k = 0; k < 3; ++k) dt.chain[k].*field = v[k];
}

// The drive-train keys of an effects map (after the others, so a preset's values are in e).
void parse_drive_train(const YAML::Node& n, const std::string& file, const std::string& c, Effects& e) {
  DriveTrain& dt = e.drive;
  const auto key = [&](const char* k) { return c + "." + k; };
  const auto chains = [&](const char* k, double DriveChain::*field, const Range& r) {
    if (const YAML::Node v = n[k]) set_chains(dt, field, per_chain(v, file, key(k), r));
  };
  chains("backlash_rad", &DriveChain::backlash_rad, {0.0, 0.01, "0 to 0.01 rad (34 arcmin)"});
  chains("drive_hysteresis_rad", &DriveChain::hysteresis_rad, {0.0, 0.01, "0 to 0.01 rad"});
  chains("transmission_error_joint_rad", &DriveChain::te_joint_rad, {0.0, 0.01, "0 to 0.01 rad"});
  chains("transmission_error_motor_rad", &DriveChain::te_motor_rad, {0.0, 0.01, "0 to 0.01 rad"});
  chains("stiction_excess_Nm", &DriveChain::stiction_excess_Nm, {0.0, 20.0, "0 to 20 N m"});
  chains("stribeck_speed_rad_s", &DriveChain::stribeck_speed_rad_s, {1e-4, 1.0, "1e-4 to 1 rad/s"});
  chains("friction_load_coefficient", &DriveChain::load_friction, {0.0, 0.5, "0 to 0.5 N m per N m"});
  chains("torque_constant_delta", &DriveChain::torque_constant_delta, {-0.5, 0.5, "-0.5 to 0.5"});
  chains("cogging_Nm", &DriveChain::cogging_Nm, {0.0, 5.0, "0 to 5 N m"});
  if (const YAML::Node v = n["transmission_error_motor_order"])
    dt.te_motor_order = static_cast<int>(yaml_integer(v, file, key("transmission_error_motor_order"), 1, 10));
  if (const YAML::Node v = n["cogging_periods_per_motor_rev"])
    dt.cogging_periods_per_motor_rev = static_cast<int>(yaml_integer(v, file, key("cogging_periods_per_motor_rev"), 1, 1000));
  const Range rk{1e3, 1e6, "1e3 to 1e6 N m/rad, K1 <= K2 <= K3"};
  if (const YAML::Node v = n["drive_stiffness_Nm_per_rad"]) {
    const std::string k = key("drive_stiffness_Nm_per_rad");
    const auto K = v.IsScalar() ? std::array<std::array<double, 3>, 3>{} : per_chain_bands<3>(v, file, k, rk, "a list of three bands K1, K2, K3");
    const double one = v.IsScalar() ? bounded(v, file, k, rk) : 0.0;
    for (size_t i = 0; i < 3; ++i) {
      dt.chain[i].stiffness_Nm_per_rad = v.IsScalar() ? std::array<double, 3>{one, one, one} : K[i];
      const auto& Ki = dt.chain[i].stiffness_Nm_per_rad;
      if (Ki[1] < Ki[0] || Ki[2] < Ki[1])
        throw InputError(yaml_where(file, v, k) + fmt::format("chain {}: the bands must not soften (valid: {})", i + 1, rk.what));
    }
  }
  if (const YAML::Node v = n["drive_stiffness_bands_Nm"]) {
    const std::string k = key("drive_stiffness_bands_Nm");
    const auto T = per_chain_bands<2>(v, file, k, {0.01, 1000.0, "0.01 to 1000 N m, T1 < T2"}, "a list of two torques T1, T2");
    for (size_t i = 0; i < 3; ++i) {
      if (!(T[i][0] < T[i][1]))
        throw InputError(yaml_where(file, v, k) + fmt::format("chain {}: T1 = {} must be below T2 = {}", i + 1, T[i][0], T[i][1]));
      dt.chain[i].band_Nm = T[i];
    }
  }
  for (size_t i = 0; i < 3; ++i) {
    const auto& Ki = dt.chain[i].stiffness_Nm_per_rad;
    if ((Ki[0] != Ki[1] || Ki[1] != Ki[2]) && !(dt.chain[i].band_Nm[0] > 0.0))
      throw InputError(yaml_where(file, n, c) + fmt::format("drive_stiffness_Nm_per_rad: chain {} has bands of "
                                                            "different stiffness: give drive_stiffness_bands_Nm [T1, T2]", i + 1));
  }
}

// --- Encoder harmonics, latch jitter, base-plate growth (sim/encoder_error.hpp) ---

// encoder_harmonics: a list of up to kMaxEncoderHarmonics maps {order, amplitude_rad}.
void parse_harmonics(const YAML::Node& n, const std::string& file, const std::string& c, Effects& e) {
  if (!n.IsSequence() || n.size() > static_cast<size_t>(kMaxEncoderHarmonics))
    throw InputError(yaml_where(file, n, c) + fmt::format("expected a list of up to {} maps {{order, amplitude_rad}}",
                                                          kMaxEncoderHarmonics));
  for (size_t h = 0; h < n.size(); ++h) {
    const std::string ch = fmt::format("{}[{}]", c, h);
    yaml_check_keys(n[h], file, ch, {"order", "amplitude_rad"});
    if (!n[h]["order"] || !n[h]["amplitude_rad"])
      throw InputError(yaml_where(file, n[h], ch) + "needs order (2 to 65536 per motor revolution) and amplitude_rad");
    e.encoder_harmonics[h].order = static_cast<int>(yaml_integer(n[h]["order"], file, ch + ".order", 2, 65536));
    e.encoder_harmonics[h].amplitude_rad =
        per_chain(n[h]["amplitude_rad"], file, ch + ".amplitude_rad", {0.0, 0.01, "0 to 0.01 rad"});
  }
}

// hub_pin_offset_um: three pairs [x, y] (um, hub frame), one per chain; stored in metres.
void parse_hub_pins(const YAML::Node& n, const std::string& file, const std::string& c, Effects& e) {
  const char* what = "a list of three pairs [x, y] in um (one per chain, hub frame)";
  if (!n.IsSequence() || n.size() != 3) throw InputError(yaml_where(file, n, c) + fmt::format("expected {}", what));
  const Range r{-100.0, 100.0, "-100 to 100 um"};
  for (size_t i = 0; i < 3; ++i) {
    const std::string ci = fmt::format("{}[{}]", c, i);
    if (!n[i].IsSequence() || n[i].size() != 2) throw InputError(yaml_where(file, n[i], ci) + fmt::format("expected {}", what));
    for (size_t k = 0; k < 2; ++k)
      e.mjcf.hub_pin_m[i][k] = 1e-6 * bounded(n[i][k], file, fmt::format("{}[{}]", ci, k), r);
  }
}

// The keys of this block under effects (each optional).
void parse_encoder_and_geometry(const YAML::Node& n, const std::string& file, Effects& e) {
  if (const YAML::Node v = n["encoder_harmonics"]) parse_harmonics(v, file, "effects.encoder_harmonics", e);
  if (const YAML::Node v = n["encoder_jitter_s"])
    e.encoder_jitter_s = per_chain(v, file, "effects.encoder_jitter_s", {0.0, 1e-3, "0 to 1e-3 s"});
  if (const YAML::Node v = n["hub_pin_offset_um"]) parse_hub_pins(v, file, "effects.hub_pin_offset_um", e);
}

// thermal.base_expansion_per_K, thermal.base_time_constant_s (absent: as the links).
void parse_base_thermal(const YAML::Node& t, const std::string& file, const std::string& ct, ThermalEffect& th) {
  if (t["base_expansion_per_K"])
    th.base_expansion_per_K = bounded(t["base_expansion_per_K"], file, ct + ".base_expansion_per_K", {0.0, 1e-3, "0 to 1e-3 per K"});
  if (t["base_time_constant_s"])
    th.base_time_constant_s = bounded(t["base_time_constant_s"], file, ct + ".base_time_constant_s", {1.0, 1e6, "1 to 1e6 s"});
}

// Phase of every harmonic slot of every encoder, uniform on [0, 2 pi), from its
// own stream (the slots are always all drawn: a phase does not depend on how
// many harmonics a scenario lists).
void draw_harmonic_phases(std::uint64_t stream_seed, Effects& e) {
  Rng rng(stream_seed);
  for (EncoderHarmonic& h : e.encoder_harmonics)
    for (double& ph : h.phase_rad) ph = rng.uniform(0.0, 2.0 * std::numbers::pi);
}

}  // namespace

Effects parse_effects(const YAML::Node& n, const std::string& file, std::uint64_t seed, const DataSheet& sheet) {
  const std::string c = "effects";
  Effects e;
  if (n.IsScalar()) {
    e = preset(n, file, c, seed, sheet);
  } else {
    if (!n.IsMap())
      throw InputError(yaml_where(file, n, c) + "expected ideal, realistic, randomized or a map of effects (scenarios/SCHEMA.md)");
    yaml_check_keys(n, file, c,
                    {// drive train (sim/drive_train.hpp)
                     "backlash_rad", "drive_stiffness_Nm_per_rad", "drive_stiffness_bands_Nm", "drive_hysteresis_rad",
                     "transmission_error_joint_rad", "transmission_error_motor_rad", "transmission_error_motor_order",
                     "stiction_excess_Nm", "stribeck_speed_rad_s", "friction_load_coefficient",
                     "torque_constant_delta", "cogging_Nm", "cogging_periods_per_motor_rev",
                     "preset", "transmission_compliance_rad_per_Nm", "passive_clearance_mm", "coulomb_friction_Nm",
                     "viscous_friction_Nm_s", "friction_timeconst_s", "thermal", "encoder_cyclic_rad", "encoder_skew_s", "gear_ratio",
                     // encoder harmonics, latch jitter, hub pins (parse_encoder_and_geometry)
                     "encoder_harmonics", "encoder_jitter_s", "hub_pin_offset_um"});
    if (n["preset"]) e = preset(n["preset"], file, c + ".preset", seed, sheet);
    const auto key = [&](const char* k) { return c + "." + k; };
    if (const YAML::Node v = n["transmission_compliance_rad_per_Nm"])
      e.mjcf.compliance_rad_per_Nm =
          per_chain(v, file, key("transmission_compliance_rad_per_Nm"), {0.0, 1.0, "0 (rigid) to 1 rad/N m"});
    if (const YAML::Node v = n["passive_clearance_mm"])
      e.mjcf.clearance_m = per_chain(v, file, key("passive_clearance_mm"), {0.0, 1.0, "0 to 1 mm"}, kMetresPerMm);
    if (const YAML::Node v = n["coulomb_friction_Nm"])
      e.mjcf.coulomb_Nm = per_chain(v, file, key("coulomb_friction_Nm"), {0.0, 20.0, "0 to 20 N m"});
    if (const YAML::Node v = n["viscous_friction_Nm_s"])
      e.mjcf.viscous_Nm_s = per_chain(v, file, key("viscous_friction_Nm_s"), {0.0, 100.0, "0 to 100 N m s/rad"});
    if (const YAML::Node v = n["friction_timeconst_s"])
      e.mjcf.friction_timeconst_s = bounded(
          v, file, key("friction_timeconst_s"),
          {0.0, 1.0, "0 (two physics steps: as stiff as MuJoCo allows) to 1 s; MuJoCo's default 0.02"});
    if (const YAML::Node v = n["encoder_cyclic_rad"])
      e.encoder_cyclic_rad = per_chain(v, file, key("encoder_cyclic_rad"), {0.0, 0.01, "0 to 0.01 rad"});
    if (const YAML::Node v = n["encoder_skew_s"]) {
      const Range r{-0.01, 0.01, "-0.01 to 0.01 s"};
      // A number: encoders 2 and 3 latched this long after encoder 1.
      e.encoder_skew_s = yaml_number_or_three(
          v, file, key("encoder_skew_s"), kPerChain,
          [&](const YAML::Node& x, const std::string& k) { return bounded(x, file, k, r); },
          [](double s) { return std::array<double, 3>{0.0, s, s}; });
    }
    if (const YAML::Node v = n["gear_ratio"])
      e.gear_ratio = bounded(v, file, key("gear_ratio"), {1.0, 200.0, "1 (direct drive) to 200"});
    if (const YAML::Node t = n["thermal"]) {
      const std::string ct = key("thermal");
      if (!t.IsMap()) throw InputError(yaml_where(file, t, ct) + "expected {expansion_per_K, rise_K, time_constant_s}");
      yaml_check_keys(t, file, ct, {"expansion_per_K", "rise_K", "time_constant_s", "base_expansion_per_K",
                                    "base_time_constant_s"});
      if (t["expansion_per_K"])
        e.thermal.expansion_per_K = bounded(t["expansion_per_K"], file, ct + ".expansion_per_K", {0.0, 1e-3, "0 to 1e-3 per K"});
      if (t["rise_K"]) e.thermal.rise_K = bounded(t["rise_K"], file, ct + ".rise_K", {-50.0, 100.0, "-50 to 100 K"});
      if (t["time_constant_s"])
        e.thermal.time_constant_s =
            bounded(t["time_constant_s"], file, ct + ".time_constant_s", {1.0, 1e6, "1 to 1e6 s"});
      parse_base_thermal(t, file, ct, e.thermal);
    }
    parse_drive_train(n, file, c, e);
    parse_encoder_and_geometry(n, file, e);
  }
  Rng rng(derive_seed(seed, Stream::kEncoderErrors));
  for (double& ph : e.encoder_phase_rad) ph = rng.uniform(0.0, 2.0 * std::numbers::pi);
  Rng drive_rng(derive_seed(seed, Stream::kDriveTrainPhases));  // drive-train phases: TE per joint and per motor revolution, cogging
  for (DriveChain& d : e.drive.chain)
    for (double* ph : {&d.te_joint_phase_rad, &d.te_motor_phase_rad, &d.cogging_phase_rad})
      *ph = drive_rng.uniform(0.0, 2.0 * std::numbers::pi);
  draw_harmonic_phases(derive_seed(seed, Stream::kHarmonicPhases), e);
  return e;
}

}  // namespace gpm::sim
