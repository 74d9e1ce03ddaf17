// Tests of sim/effects_yaml.cpp (through the scenario parser of sim/scenario.cpp):
// every key lands where it belongs with its unit, presets and overrides
// combine, absent means off, and bad values are one-line errors naming the
// file, the line and the key.
#include "sim/effects_yaml.hpp"

#include <gtest/gtest.h>

#include "models/data_dir.hpp"
#include "models/errors.hpp"
#include "sim/scenario.hpp"

namespace gpm::sim {
namespace {

const char* kBase = "sampling: {pattern: disc, radius: 10, count: 3}\n";

Scenario parse(const std::string& effects, const std::string& extra = "") {
  return parse_scenario(std::string(kBase) + extra + "effects: " + effects + "\n", "s.yaml", gpm::models_dir());
}

std::string error_of(const std::string& effects, const std::string& extra = "") {
  try {
    parse(effects, extra);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

const char* kFast = "physics: {timestep_s: 0.00025}\nservo: {rate_hz: 4000}\n";

TEST(EffectsYaml, AbsentAndIdealAreOff) {
  const Scenario none = parse_scenario(kBase, "s.yaml", gpm::models_dir());
  EXPECT_FALSE(none.twin.effects.any());
  EXPECT_FALSE(parse("ideal").twin.effects.any());
}

TEST(EffectsYaml, KeysLandInTheirUnits) {
  const Effects e = parse(
      "{transmission_compliance_rad_per_Nm: [1e-4, 2e-4, 3e-4], passive_clearance_mm: 0.005, "
      "coulomb_friction_Nm: 0.3, viscous_friction_Nm_s: [0.1, 0.2, 0.3], encoder_cyclic_rad: 2e-5, "
      "encoder_skew_s: 1e-4, thermal: {expansion_per_K: 23e-6, rise_K: 3, time_constant_s: 100}}",
      kFast).twin.effects;
  EXPECT_DOUBLE_EQ(e.mjcf.compliance_rad_per_Nm[1], 2e-4);
  EXPECT_DOUBLE_EQ(e.mjcf.clearance_m[2], 0.005e-3);  // mm in the file, m in the model
  EXPECT_DOUBLE_EQ(e.mjcf.coulomb_Nm[0], 0.3);
  EXPECT_DOUBLE_EQ(e.mjcf.viscous_Nm_s[2], 0.3);
  EXPECT_DOUBLE_EQ(e.encoder_cyclic_rad[1], 2e-5);
  EXPECT_DOUBLE_EQ(e.encoder_skew_s[0], 0.0);  // a scalar: encoders 2 and 3 relative to encoder 1
  EXPECT_DOUBLE_EQ(e.encoder_skew_s[2], 1e-4);
  EXPECT_DOUBLE_EQ(e.thermal.growth(100.0), 23e-6 * 3.0 * (1.0 - std::exp(-1.0)));
  // The drives' friction time constant: two physics steps (0) unless given.
  EXPECT_DOUBLE_EQ(e.mjcf.friction_timeconst_s, 0.0);
  EXPECT_DOUBLE_EQ(parse("{preset: realistic, friction_timeconst_s: 0.02}", kFast).twin.effects.mjcf.friction_timeconst_s, 0.02);
}

TEST(EffectsYaml, PresetWithOverridesAndSeededPhases) {
  const Effects r = realistic_effects();
  const Effects e = parse("{preset: realistic, coulomb_friction_Nm: 0}", kFast).twin.effects;
  EXPECT_DOUBLE_EQ(e.mjcf.coulomb_Nm[1], 0.0);
  EXPECT_DOUBLE_EQ(e.mjcf.compliance_rad_per_Nm[0], r.mjcf.compliance_rad_per_Nm[0]);
  EXPECT_DOUBLE_EQ(e.thermal.expansion_per_K, 23e-6);
  // Phases: fixed by the scenario seed, different per encoder and per seed.
  const Effects same = parse("realistic", kFast).twin.effects;
  EXPECT_EQ(e.encoder_phase_rad, same.encoder_phase_rad);
  EXPECT_NE(e.encoder_phase_rad[0], e.encoder_phase_rad[1]);
  const Effects other = parse("realistic", std::string(kFast) + "seed: 99\n").twin.effects;
  EXPECT_NE(other.encoder_phase_rad[0], e.encoder_phase_rad[0]);
}

TEST(EffectsYaml, BadValuesNameFileLineAndKey) {
  const std::string neg = error_of("{transmission_compliance_rad_per_Nm: -1e-4}", kFast);
  EXPECT_NE(neg.find("s.yaml:4: effects.transmission_compliance_rad_per_Nm"), std::string::npos) << neg;
  const std::string two = error_of("{passive_clearance_mm: [0.01, 0.01]}");
  EXPECT_NE(two.find("effects.passive_clearance_mm"), std::string::npos) << two;
  EXPECT_NE(two.find("list of 2"), std::string::npos) << two;
  const std::string unknown = error_of("{coulomb_friction: 0.3}");
  EXPECT_NE(unknown.find("effects.coulomb_friction"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("coulomb_friction_Nm"), std::string::npos) << unknown;
  EXPECT_NE(error_of("optimistic").find("not a preset"), std::string::npos);
  const std::string slow = error_of("{friction_timeconst_s: 2}", kFast);
  EXPECT_NE(slow.find("s.yaml:4: effects.friction_timeconst_s"), std::string::npos) << slow;
  EXPECT_NE(slow.find("0 (two physics steps"), std::string::npos) << slow;
  EXPECT_NE(error_of("{thermal: {rise_K: 3, time_constant_s: 0}}").find("effects.thermal.time_constant_s"),
            std::string::npos);
  // A stiffness the timestep cannot integrate is refused at parse time, with the line.
  const std::string stiff = error_of("{transmission_compliance_rad_per_Nm: 1e-7}", kFast);
  EXPECT_NE(stiff.find("s.yaml:4:"), std::string::npos) << stiff;
  EXPECT_NE(stiff.find("too stiff"), std::string::npos) << stiff;
}

}  // namespace
}  // namespace gpm::sim
