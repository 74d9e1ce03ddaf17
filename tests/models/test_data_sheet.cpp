// Tests of models/data_sheet.cpp: the GPM2002's data sheet in
// models/gpm2002.yaml, the forms of a stated value, the lossless round trip,
// and one clear error line per bad key.
#include "models/data_sheet.hpp"

#include <cmath>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "models/data_dir.hpp"
#include "models/errors.hpp"
#include "models/robot_yaml.hpp"
#include "models/yaml_util.hpp"

namespace gpm {
namespace {

DataSheet parse(const std::string& text) {
  return data_sheet_from_yaml(load_yaml_string(text, "r.yaml"), "r.yaml", "data_sheet");
}

std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.find('\n'), std::string::npos) << "one line";
    return m;
  }
  return "";
}

// The robot file states the GPM2002's class (a 400 W AC servo, 17-bit
// encoder, 10:1 planetary): the numbers of its comments.
TEST(DataSheet, Gpm2002FileStatesItsClass) {
  const DataSheet d = load_robot(gpm::models_dir() + "/gpm2002.yaml").data_sheet;
  EXPECT_EQ(d.gear_ratio, 10.0);
  EXPECT_EQ(d.encoder_bits, 17);
  EXPECT_EQ(d.cogging_periods, 24);  // 12 slots, 8 poles
  EXPECT_EQ(d.rotor_inertia_kg_m2, (Stated{2.6e-5, 0.9, 1.1}));
  EXPECT_EQ(d.coulomb_Nm, (Stated{0.3, 0.5, 2.0}));
  EXPECT_EQ(d.viscous_Nm_s, (Stated{0.15, 0.5, 2.0}));
  EXPECT_EQ(d.stiffness_Nm_per_rad.nominal, 1e4);
  EXPECT_EQ(d.encoder_accuracy_rad, (Stated{2e-5, 0.0, 1.0}));
  EXPECT_EQ(d.transmission_error_rad, (Stated{4.3633e-4, 0.0, 1.0}));  // 1.5 arcmin
  // The error once per joint revolution: the reducer's alone behind 10:1 (the
  // encoder's repeats per motor revolution); both in quadrature on a direct drive.
  EXPECT_EQ(d.joint_harmonic_max_rad(), 4.3633e-4);
  DataSheet direct = d;
  direct.gear_ratio = 1.0;
  EXPECT_DOUBLE_EQ(direct.joint_harmonic_max_rad(), std::hypot(4.3633e-4, 2e-5));
  EXPECT_EQ(d.latch_skew_s.nominal, 50e-6);
  EXPECT_EQ(d.clearance_mm.max(), 0.01);  // up to twice 5 um
  EXPECT_NEAR(d.reflected_inertia_kg_m2(), 0.0026, 1e-15);  // 0.26e-4 kg m^2 x 10^2
  EXPECT_EQ(d.compliance_rad_per_Nm(), 1e-4);
  // A file without the section: the same values.
  EXPECT_EQ(d, DataSheet{});
}

TEST(DataSheet, StatedValueForms) {
  const DataSheet d = parse("{coulomb_Nm: 0.4, viscous_Nm_s: {nominal: 0.2, tolerance: 0.25}, "
                            "clearance_mm: {nominal: 0.01, factor: [0, 3]}, rotor_inertia_kg_m2: {nominal: 1.0e-5}}");
  EXPECT_EQ(d.coulomb_Nm, (Stated{0.4, 1.0, 1.0}));  // a number: exact
  EXPECT_EQ(d.viscous_Nm_s, (Stated{0.2, 0.75, 1.25}));
  EXPECT_DOUBLE_EQ(d.viscous_Nm_s.max(), 0.25);
  EXPECT_EQ(d.clearance_mm, (Stated{0.01, 0.0, 3.0}));
  EXPECT_EQ(d.rotor_inertia_kg_m2, (Stated{1e-5, 1.0, 1.0}));
  EXPECT_EQ(d.stiffness_Nm_per_rad, DataSheet{}.stiffness_Nm_per_rad);  // left out: the GPM2002's
}

TEST(DataSheet, RoundTripIsBitExact) {
  DataSheet d;
  d.gear_ratio = 7.3;
  d.encoder_bits = 20;
  d.cogging_periods = 0;
  d.coulomb_Nm = {0.1 + 0.2, 1.0 / 3.0, 2.5};
  d.latch_skew_s = {1.0 / 7.0 * 1e-4, 0.0, 2.0};
  const std::string text = data_sheet_to_yaml(d);
  EXPECT_EQ(data_sheet_from_yaml(load_yaml_string(text, "r.yaml")["data_sheet"], "r.yaml", "data_sheet"), d) << text;
  Robot r;
  r.data_sheet = d;
  EXPECT_EQ(parse_robot(robot_to_yaml(r), "r.yaml"), r);
}

TEST(DataSheet, BadKeysGiveOneClearLine) {
  EXPECT_EQ(error_of("{coulomb_Nm: -0.3}"),
            "r.yaml:1: data_sheet.coulomb_Nm: -0.3 is out of range (valid: 0 to 20 N m)");
  EXPECT_EQ(error_of("{rotor_inertia_kg_m2: 0}"),
            "r.yaml:1: data_sheet.rotor_inertia_kg_m2: 0 is out of range (valid: > 0 to 0.01 kg m^2)");
  EXPECT_EQ(error_of("{viscous_Nm_s: {nominal: 0.1, tolerance: 1.5}}"),
            "r.yaml:1: data_sheet.viscous_Nm_s.tolerance: 1.5 is out of range (valid: 0 to 1 (a fraction: 0.1 is +-10 %))");
  EXPECT_EQ(error_of("{clearance_mm: {nominal: 0.005, factor: [1.5, 2]}}"),
            "r.yaml:1: data_sheet.clearance_mm.factor[0]: 1.5 is out of range (valid: 0 to 1 (a factor))");
  EXPECT_NE(error_of("{clearance_mm: {nominal: 0.005, factor: 2}}").find("data_sheet.clearance_mm.factor: expected [lo, hi]"),
            std::string::npos);
  EXPECT_NE(error_of("{coulomb_Nm: {nominal: 0.3, tolerance: 0.1, factor: [0.5, 2]}}").find("not both"), std::string::npos);
  EXPECT_NE(error_of("{coulomb_Nm: {tolerance: 0.1}}").find("data_sheet.coulomb_Nm: missing key 'nominal'"), std::string::npos);
  EXPECT_NE(error_of("{coulomb: 0.3}").find("data_sheet"), std::string::npos);  // unknown key, nearest named
  EXPECT_NE(error_of("{encoder_bits: 17.5}").find("data_sheet.encoder_bits"), std::string::npos);
  EXPECT_NE(error_of("{gear_ratio: 0.5}").find("data_sheet.gear_ratio: 0.5 is out of range"), std::string::npos);
  EXPECT_NE(error_of("{cogging_periods: -1}").find("data_sheet.cogging_periods"), std::string::npos);
  EXPECT_NE(error_of("{cogging_periods: 2.5}").find("data_sheet.cogging_periods"), std::string::npos);
  EXPECT_NE(error_of("[1, 2]").find("data_sheet: expected a map"), std::string::npos);
  // Inside a robot file the key path is the robot's.
  try {
    parse_robot("name: R\ngeometry: {xa1: 0, ya1: 250, xa2: 433, ya2: 0, xa3: 433, ya3: 500, la1: 244, la2: 244, "
                "la3: 244, lb1: 244, lb2: 244, lb3: 244, dth1: 0, dth2: 0, dth3: 0}\ndata_sheet: {latch_skew_s: 1}\n",
                "robot.yaml");
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "robot.yaml:3: data_sheet.latch_skew_s: 1 is out of range (valid: 0 to 0.005 s)");
  }
}

}  // namespace
}  // namespace gpm
