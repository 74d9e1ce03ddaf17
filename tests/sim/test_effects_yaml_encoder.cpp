// Tests of sim/effects_yaml.cpp, the block of the encoder harmonics, latch
// jitter, hub pin and base-plate keys (through the scenario parser of
// sim/scenario.cpp): keys land in their units, absent keys leave the ideal
// twin, harmonic phases are seeded per slot and encoder (reproducible,
// different between encoders, independent of the other phases), and bad
// values are one-line errors naming the file, the line, the key and the range.
#include "sim/effects_yaml.hpp"

#include <gtest/gtest.h>

#include "models/data_dir.hpp"
#include "models/errors.hpp"
#include "sim/scenario.hpp"

namespace gpm::sim {
namespace {

const char* kBase = "sampling: {pattern: disc, radius: 10, count: 3}\n";

Effects parse(const std::string& effects, const std::string& seed = "") {
  return parse_scenario(std::string(kBase) + seed + "effects: " + effects + "\n", "s.yaml", gpm::models_dir()).twin.effects;
}

std::string error_of(const std::string& effects) {
  try {
    parse(effects);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(EffectsYamlEncoder, KeysLandInTheirUnits) {
  const Effects e = parse(
      "{gear_ratio: 10, encoder_harmonics: [{order: 2, amplitude_rad: 5e-6}, {order: 4, amplitude_rad: [1e-6, 2e-6, 3e-6]}], "
      "encoder_jitter_s: [1e-6, 2e-6, 0], thermal: {expansion_per_K: 23e-6, rise_K: 3, base_expansion_per_K: 11e-6, "
      "base_time_constant_s: 3600}}");
  EXPECT_EQ(e.gear_ratio, 10.0);
  EXPECT_EQ(e.encoder_harmonics[0].order, 2);
  EXPECT_EQ(e.encoder_harmonics[0].amplitude_rad, (std::array<double, 3>{5e-6, 5e-6, 5e-6}));
  EXPECT_EQ(e.encoder_harmonics[1].order, 4);
  EXPECT_EQ(e.encoder_harmonics[1].amplitude_rad[2], 3e-6);
  EXPECT_EQ(e.encoder_harmonics[2].order, 0) << "unused slots stay off";
  EXPECT_EQ(e.encoder_jitter_s[1], 2e-6);
  EXPECT_EQ(e.thermal.base_expansion_per_K.value_or(0.0), 11e-6);
  EXPECT_EQ(e.thermal.base_time_constant_s.value_or(0.0), 3600.0);
  EXPECT_TRUE(e.any());
  const Effects p = parse("{hub_pin_offset_um: [[8, -3], [-5, 12], [4, 6]]}");
  EXPECT_DOUBLE_EQ(p.mjcf.hub_pin_m[1][1], 12e-6) << "um to m";
  EXPECT_DOUBLE_EQ(p.mjcf.hub_pin_m[0][0], 8e-6);
  EXPECT_TRUE(p.any());
}

TEST(EffectsYamlEncoder, AbsentKeysLeaveTheIdealTwinAndTheLinksLawForTheBase) {
  const Effects e = parse("{thermal: {expansion_per_K: 23e-6, rise_K: 3}}");
  EXPECT_FALSE(e.encoder_and_geometry_on());
  EXPECT_FALSE(e.thermal.base_own());
  for (double t : {0.0, 100.0, 1e4}) EXPECT_EQ(e.thermal.base_growth(t), e.thermal.growth(t));
  EXPECT_FALSE(parse("{gear_ratio: 10}").any()) << "a gear ratio is a data-sheet value, not an effect";
}

TEST(EffectsYamlEncoder, HarmonicPhasesAreSeededPerSlotAndEncoder) {
  const std::string h = "{encoder_harmonics: [{order: 2, amplitude_rad: 5e-6}]}";
  const Effects a = parse(h, "seed: 5\n"), same = parse(h, "seed: 5\n"), other = parse(h, "seed: 6\n");
  EXPECT_EQ(a.encoder_harmonics[0].phase_rad, same.encoder_harmonics[0].phase_rad);
  EXPECT_NE(a.encoder_harmonics[0].phase_rad[0], a.encoder_harmonics[0].phase_rad[1]);
  EXPECT_NE(a.encoder_harmonics[0].phase_rad[0], a.encoder_harmonics[1].phase_rad[0]);
  EXPECT_NE(a.encoder_harmonics[0].phase_rad[0], other.encoder_harmonics[0].phase_rad[0]);
  for (double ph : a.encoder_harmonics[0].phase_rad) {
    EXPECT_GE(ph, 0.0);
    EXPECT_LE(ph, 2.0 * 3.14159266);
  }
  // The once-per-revolution phases are those of a scenario without harmonics.
  EXPECT_EQ(a.encoder_phase_rad, parse("{}", "seed: 5\n").encoder_phase_rad);
}

TEST(EffectsYamlEncoder, BadValuesNameFileLineKeyAndRange) {
  const std::string order = error_of("{encoder_harmonics: [{order: 1, amplitude_rad: 1e-6}]}");
  EXPECT_NE(order.find("s.yaml:2: effects.encoder_harmonics[0].order"), std::string::npos) << order;
  const std::string amp = error_of("{encoder_harmonics: [{order: 2, amplitude_rad: [0, 0, 0.1]}]}");
  EXPECT_NE(amp.find("effects.encoder_harmonics[0].amplitude_rad[2]"), std::string::npos) << amp;
  EXPECT_NE(amp.find("0 to 0.01 rad"), std::string::npos) << amp;
  const std::string many = error_of(
      "{encoder_harmonics: [{order: 2, amplitude_rad: 0}, {order: 3, amplitude_rad: 0}, {order: 4, amplitude_rad: 0}, "
      "{order: 5, amplitude_rad: 0}, {order: 6, amplitude_rad: 0}]}");
  EXPECT_NE(many.find("up to 4"), std::string::npos) << many;
  EXPECT_NE(error_of("{encoder_harmonics: [{order: 2}]}").find("needs order"), std::string::npos);
  const std::string jit = error_of("{encoder_jitter_s: -1e-6}");
  EXPECT_NE(jit.find("effects.encoder_jitter_s"), std::string::npos) << jit;
  EXPECT_NE(jit.find("0 to 1e-3 s"), std::string::npos) << jit;
  const std::string pins = error_of("{hub_pin_offset_um: [[1, 2], [3, 4]]}");
  EXPECT_NE(pins.find("effects.hub_pin_offset_um"), std::string::npos) << pins;
  EXPECT_NE(pins.find("three pairs"), std::string::npos) << pins;
  const std::string far = error_of("{hub_pin_offset_um: [[1, 2], [3, 400], [0, 0]]}");
  EXPECT_NE(far.find("effects.hub_pin_offset_um[1][1]"), std::string::npos) << far;
  EXPECT_NE(far.find("-100 to 100 um"), std::string::npos) << far;
  const std::string base = error_of("{thermal: {rise_K: 3, base_time_constant_s: 0}}");
  EXPECT_NE(base.find("effects.thermal.base_time_constant_s"), std::string::npos) << base;
  EXPECT_NE(error_of("{thermal: {base_expansion: 1e-5}}").find("base_expansion_per_K"), std::string::npos);
}

}  // namespace
}  // namespace gpm::sim
