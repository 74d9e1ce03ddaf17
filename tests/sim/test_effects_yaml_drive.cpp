// Tests of sim/effects_yaml.cpp, the drive-train keys (sim/drive_train.hpp):
// each key lands in its chain and unit, bands are given for all chains or per
// chain, off means off, and bad values are one-line errors naming the file,
// the line, the key and the valid range.
#include "sim/effects_yaml.hpp"

#include <gtest/gtest.h>

#include "models/data_dir.hpp"
#include "models/errors.hpp"
#include "sim/scenario.hpp"

namespace gpm::sim {
namespace {

const char* kBase = "sampling: {pattern: disc, radius: 10, count: 3}\n";
const char* kFast = "physics: {timestep_s: 0.00025}\nservo: {rate_hz: 4000}\n";

Effects parse(const std::string& effects) {
  return parse_scenario(std::string(kBase) + kFast + "effects: " + effects + "\n", "s.yaml", gpm::models_dir())
      .twin.effects;
}

std::string error_of(const std::string& effects) {
  try {
    parse(effects);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(EffectsYamlDrive, KeysLandPerChain) {
  const Effects e = parse(
      "{transmission_compliance_rad_per_Nm: 1e-4, backlash_rad: [1e-3, 2e-3, 3e-3], drive_hysteresis_rad: 3e-4, "
      "transmission_error_joint_rad: 2e-4, transmission_error_motor_rad: [1e-4, 0, 5e-5], "
      "transmission_error_motor_order: 3, stiction_excess_Nm: 0.2, stribeck_speed_rad_s: 0.005, "
      "friction_load_coefficient: [0.05, 0.1, 0.15], torque_constant_delta: [-0.05, 0, 0.08], cogging_Nm: 0.1, "
      "cogging_periods_per_motor_rev: 36}");
  const auto& c = e.drive.chain;
  EXPECT_DOUBLE_EQ(c[2].backlash_rad, 3e-3);
  EXPECT_DOUBLE_EQ(c[1].hysteresis_rad, 3e-4);
  EXPECT_DOUBLE_EQ(c[0].te_joint_rad, 2e-4);
  EXPECT_DOUBLE_EQ(c[1].te_motor_rad, 0.0);
  EXPECT_DOUBLE_EQ(c[2].te_motor_rad, 5e-5);
  EXPECT_EQ(e.drive.te_motor_order, 3);
  EXPECT_DOUBLE_EQ(c[1].stiction_excess_Nm, 0.2);
  EXPECT_DOUBLE_EQ(c[0].stribeck_speed_rad_s, 0.005);
  EXPECT_DOUBLE_EQ(c[1].load_friction, 0.1);
  EXPECT_DOUBLE_EQ(c[0].torque_constant_delta, -0.05);
  EXPECT_DOUBLE_EQ(c[2].cogging_Nm, 0.1);
  EXPECT_EQ(e.drive.cogging_periods_per_motor_rev, 36);
  EXPECT_NE(c[0].te_joint_phase_rad, c[1].te_joint_phase_rad) << "phases are drawn per chain";
  EXPECT_TRUE(e.any());
  EXPECT_FALSE(parse("{backlash_rad: 0, cogging_Nm: 0}").any());
}

TEST(EffectsYamlDrive, BandsForAllChainsOrPerChain) {
  const Effects all = parse("{drive_stiffness_Nm_per_rad: [1.3e4, 1.8e4, 2.3e4], drive_stiffness_bands_Nm: [7, 25]}");
  for (const DriveChain& c : all.drive.chain) {
    EXPECT_DOUBLE_EQ(c.stiffness_Nm_per_rad[2], 2.3e4);
    EXPECT_DOUBLE_EQ(c.band_Nm[1], 25.0);
  }
  const Effects per = parse(
      "{drive_stiffness_Nm_per_rad: [[7e3, 8e3, 9e3], [1e4, 1e4, 1e4], [1.3e4, 1.8e4, 2.3e4]], "
      "drive_stiffness_bands_Nm: [[2, 15], [3, 20], [7, 25]]}");
  EXPECT_DOUBLE_EQ(per.drive.chain[0].stiffness_Nm_per_rad[1], 8e3);
  EXPECT_DOUBLE_EQ(per.drive.chain[1].band_Nm[0], 3.0);
  const Effects one = parse("{drive_stiffness_Nm_per_rad: 1e4}");
  EXPECT_DOUBLE_EQ(one.drive.chain[2].stiffness_Nm_per_rad[1], 1e4);
}

TEST(EffectsYamlDrive, BadValuesNameFileLineKeyAndRange) {
  const std::string big = error_of("{backlash_rad: 0.1}");
  EXPECT_NE(big.find("s.yaml:4: effects.backlash_rad"), std::string::npos) << big;
  EXPECT_NE(big.find("0 to 0.01 rad"), std::string::npos) << big;
  const std::string soft = error_of("{drive_stiffness_Nm_per_rad: [2e4, 1e4, 3e4], drive_stiffness_bands_Nm: [7, 25]}");
  EXPECT_NE(soft.find("effects.drive_stiffness_Nm_per_rad"), std::string::npos) << soft;
  EXPECT_NE(soft.find("soften"), std::string::npos) << soft;
  const std::string bands = error_of("{drive_stiffness_Nm_per_rad: [1e4, 2e4, 3e4]}");
  EXPECT_NE(bands.find("drive_stiffness_bands_Nm"), std::string::npos) << bands;
  const std::string order = error_of("{drive_stiffness_Nm_per_rad: 1e4, drive_stiffness_bands_Nm: [25, 7]}");
  EXPECT_NE(order.find("T1 = 25 must be below T2 = 7"), std::string::npos) << order;
  const std::string shape = error_of("{drive_stiffness_Nm_per_rad: [1e4, 2e4]}");
  EXPECT_NE(shape.find("list of three bands"), std::string::npos) << shape;
  EXPECT_NE(error_of("{cogging_periods_per_motor_rev: 2.5}").find("effects.cogging_periods_per_motor_rev"),
            std::string::npos);
  EXPECT_NE(error_of("{torque_constant_delta: [0, 0.9, 0]}").find("effects.torque_constant_delta[1]"), std::string::npos)
      << error_of("{torque_constant_delta: [0, 0.9, 0]}");
  // A mesh without a rotor, and bands too stiff for the timestep, are refused at parse time with the line.
  const std::string rotor = error_of("{backlash_rad: 1e-3}");
  EXPECT_NE(rotor.find("s.yaml:4:"), std::string::npos) << rotor;
  EXPECT_NE(rotor.find("compliance > 0"), std::string::npos) << rotor;
  const std::string stiff = error_of("{drive_stiffness_Nm_per_rad: 1e5}");
  EXPECT_NE(stiff.find("too stiff"), std::string::npos) << stiff;
}

}  // namespace
}  // namespace gpm::sim
