// Tests of sim/effects_random.cpp (and the `randomized` preset of
// sim/effects_yaml.cpp): every draw lies in its documented range, chains
// differ, a log-uniform range is centred on its geometric mean, one seed is
// one robot, and every drawn robot builds a stable twin at the main job's
// timestep.
#include "sim/effects_random.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "models/data_dir.hpp"
#include "models/robot_yaml.hpp"
#include "sim/scenario.hpp"
#include "sim/twin.hpp"

namespace gpm::sim {
namespace {

bool within(double v, const EffectRange& r) { return v >= r.lo && v <= r.hi; }

TEST(EffectsRandom, EveryDrawIsInItsRangeAndChainsDiffer) {
  const RandomizedRanges r;
  const DataSheet sheet;
  Rng rng(7);
  for (int n = 0; n < 200; ++n) {
    const Effects e = randomized_effects(rng, sheet, r);
    for (size_t i = 0; i < 3; ++i) {
      EXPECT_TRUE(within(e.mjcf.clearance_m[i] * 1e3, r.clearance_mm));
      // Friction within the data sheet's tolerance (viscous: with the model's 0.05 N m s/rad).
      EXPECT_GE(e.mjcf.coulomb_Nm[i], sheet.coulomb_Nm.min());
      EXPECT_LE(e.mjcf.coulomb_Nm[i], sheet.coulomb_Nm.max());
      EXPECT_GE(e.mjcf.viscous_Nm_s[i] + MjcfOptions{}.active_damping, sheet.viscous_Nm_s.min() - 1e-15);
      EXPECT_LE(e.mjcf.viscous_Nm_s[i] + MjcfOptions{}.active_damping, sheet.viscous_Nm_s.max() + 1e-15);
      EXPECT_TRUE(within(e.encoder_cyclic_rad[i], r.encoder_cyclic_rad));
      EXPECT_TRUE(within(e.encoder_skew_s[i], r.skew_s));
    }
    EXPECT_TRUE(within(e.thermal.expansion_per_K, r.expansion_per_K));
    EXPECT_TRUE(within(e.thermal.rise_K, r.rise_K));
    EXPECT_TRUE(within(e.thermal.time_constant_s, r.time_constant_s));
    EXPECT_EQ(e.gear_ratio, sheet.gear_ratio);
    EXPECT_TRUE(e.drive.any());               // the drive train drawn too (sim/drive_train.hpp)
    EXPECT_TRUE(e.encoder_and_geometry_on());  // and the encoder and geometry effects
    // Continuous draws: two chains equal would mean one value shared.
    EXPECT_NE(e.mjcf.coulomb_Nm[0], e.mjcf.coulomb_Nm[1]);
    EXPECT_NE(e.mjcf.clearance_m[1], e.mjcf.clearance_m[2]);
    EXPECT_TRUE(e.any());
  }
}

TEST(EffectsRandom, LogUniformIsCentredOnTheGeometricMean) {
  // log v uniform on [log lo, log hi]: its median is sqrt(lo hi), and a
  // quarter of the draws lie below lo^(3/4) hi^(1/4).
  const EffectRange r{0.1, 0.8, true};
  Rng rng(11);
  std::vector<double> v(4000);
  for (double& x : v) x = r.draw(rng);
  std::sort(v.begin(), v.end());
  EXPECT_NEAR(std::log(v[v.size() / 2]), std::log(std::sqrt(0.1 * 0.8)), 0.05);
  EXPECT_NEAR(std::log(v[v.size() / 4]), 0.75 * std::log(0.1) + 0.25 * std::log(0.8), 0.05);
}

Scenario with_effects(const std::string& effects, int seed) {
  const std::string text = "seed: " + std::to_string(seed) +
                           "\nphysics: {timestep_s: 0.00025}\nservo: {rate_hz: 4000}\n"
                           "sampling: {pattern: disc, radius: 10, count: 3}\neffects: " + effects + "\n";
  return parse_scenario(text, "s.yaml", gpm::models_dir());
}

TEST(EffectsRandom, OneSeedIsOneRobot) {
  const Effects a = with_effects("randomized", 5).twin.effects, b = with_effects("randomized", 5).twin.effects;
  const Effects c = with_effects("randomized", 6).twin.effects;
  EXPECT_EQ(a.mjcf.coulomb_Nm, b.mjcf.coulomb_Nm);
  EXPECT_EQ(a.encoder_cyclic_rad, b.encoder_cyclic_rad);
  EXPECT_EQ(a.encoder_phase_rad, b.encoder_phase_rad);
  EXPECT_NE(a.mjcf.coulomb_Nm, c.mjcf.coulomb_Nm);
  // A key after the preset overrides the drawn value and keeps the rest.
  const Effects d = with_effects("{preset: randomized, coulomb_friction_Nm: 0.2}", 5).twin.effects;
  EXPECT_EQ(d.mjcf.coulomb_Nm, (std::array<double, 3>{0.2, 0.2, 0.2}));
  EXPECT_EQ(d.mjcf.viscous_Nm_s, a.mjcf.viscous_Nm_s);
}

TEST(EffectsRandom, TheActualMassesLieWithinTheDataSheetsTolerance) {
  const DataSheet sheet;
  const Scenario a = with_effects("randomized", 5), b = with_effects("randomized", 6);
  EXPECT_NE(a.twin.mjcf.active_link_mass_kg, b.twin.mjcf.active_link_mass_kg);
  for (const Scenario* s : {&a, &b}) {
    EXPECT_GE(s->twin.mjcf.active_link_mass_kg, sheet.active_link_mass_kg.min());
    EXPECT_LE(s->twin.mjcf.active_link_mass_kg, sheet.active_link_mass_kg.max());
    EXPECT_GE(s->twin.mjcf.armature_kg_m2, sheet.rotor_inertia_kg_m2.min() * 100.0);
    EXPECT_LE(s->twin.mjcf.armature_kg_m2, sheet.rotor_inertia_kg_m2.max() * 100.0);
  }
  // Another preset keeps the model's design values.
  EXPECT_EQ(with_effects("realistic", 5).twin.mjcf.active_link_mass_kg, MjcfOptions{}.active_link_mass_kg);
}

TEST(EffectsRandom, EveryDrawnRobotBuildsAStableTwinAtTheMainJobsStep) {
  // The stiffest transmission of the range must pass the twin's stability
  // check (omega dt <= 1.5) at the main job's 0.25 ms step and 4 kHz loop.
  const Robot robot = load_robot(gpm::models_dir() + "/gpm2002.yaml");
  Rng rng(3);
  for (int n = 0; n < 5; ++n) {
    TwinConfig c;
    c.mjcf.timestep_s = 0.00025;
    c.servo_rate_hz = 4000.0;
    c.effects = randomized_effects(rng);
    draw_masses_within(rng, DataSheet{}, c.mjcf);
    for (ServoDrive& d : c.drives) d.kv *= c.mjcf.armature_kg_m2 / MjcfOptions{}.armature_kg_m2;  // tuned to the rotor
    const TwinModel model(robot, c);
    TwinState state(model, 1);
    for (int k = 0; k < 400; ++k) twin_step(model, state);  // 0.1 s holding home
    EXPECT_LT(state.last.violation_m, 1e-6);
    EXPECT_LT((state.last.ee_mm - robot.home).norm(), 0.5);
  }
}

}  // namespace
}  // namespace gpm::sim
