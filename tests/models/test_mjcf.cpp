// Tests of models/mjcf.cpp (text only; tests/sim/test_twin.cpp compiles the
// MJCF with MuJoCo and checks the loop closure): the committed nominal model
// equals the generator output, bodies sit at the IK of the actual parameters,
// millimetres become metres, and parameters that cannot assemble are refused;
// effects (off by default: the committed model) add the rotor bodies, the
// clearance slides and the friction where MjcfEffects says.
#include "models/mjcf.hpp"
#include "models/data_dir.hpp"

#include <fstream>
#include <regex>
#include <sstream>

#include <gtest/gtest.h>

#include "models/errors.hpp"
#include "models/kinematics.hpp"
#include "models/robot_yaml.hpp"
#include "models/yaml_util.hpp"

namespace gpm {
namespace {

const std::string kXmlPath = gpm::models_dir() + "/gpm2002.xml";

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The value of attribute attr of the element named name.
std::string attribute(const std::string& xml, const std::string& name, const std::string& attr) {
  const std::regex re("name=\"" + name + "\"[^>]*?\\b" + attr + "=\"([^\"]*)\"");
  std::smatch m;
  if (!std::regex_search(xml, m, re)) return "<missing>";
  return m[1];
}

TEST(Mjcf, CommittedNominalModelEqualsGeneratorOutput) {
  const std::string generated = mjcf_from_robot(load_robot(gpm::models_dir() + "/gpm2002.yaml"));
  EXPECT_EQ(read_text(kXmlPath), generated)
      << "models/gpm2002.xml is stale; regenerate it with: test_models_mjcf "
         "--gtest_also_run_disabled_tests --gtest_filter=Mjcf.DISABLED_RegenerateNominalModel";
}

// Writes models/gpm2002.xml (run by hand after changing the generator).
TEST(Mjcf, DISABLED_RegenerateNominalModel) {
  write_file_atomic(kXmlPath, mjcf_from_robot(load_robot(gpm::models_dir() + "/gpm2002.yaml")));
}

TEST(Mjcf, BodiesAndJointsSitAtTheActualInverseKinematics) {
  Robot r;
  r.geometry[kLa3] = 244.5;
  r.geometry[kXa3] = 433.2;
  r.geometry[kDth1] = 0.01;  // offsets do not move the mechanism
  const std::string xml = mjcf_from_robot(r);
  const JointAngles q = inverse_kinematics(r.geometry, r.home, r.branch);
  for (int i = 0; i < 3; ++i) {
    const std::string n = std::to_string(i + 1);
    EXPECT_EQ(attribute(xml, "joint_a" + n, "ref"), format_exact(q.theta_a[i]));
    EXPECT_EQ(attribute(xml, "link_a" + n, "euler"), "0 0 " + format_exact(q.theta_a[i]));
    EXPECT_EQ(attribute(xml, "joint_b" + n, "ref"), format_exact(q.theta_b[i] - q.theta_a[i]));
    EXPECT_EQ(attribute(xml, "link_b" + n, "euler"), "0 0 " + format_exact(q.theta_b[i] - q.theta_a[i]));
  }
  // Millimetres to metres: A3 = (433.2, 500) mm, la3 = 244.5 mm.
  EXPECT_EQ(attribute(xml, "link_a3", "pos"), "0.4332 0.5 0");
  EXPECT_EQ(attribute(xml, "link_b3", "pos"), "0.2445 0 0.03");
  EXPECT_EQ(attribute(xml, "close_b3", "anchor"), "0.244 0 0");
}

TEST(Mjcf, HasTheNamedPartsStiffConstraintsAndNoContacts) {
  const std::string xml = mjcf_from_robot(Robot{});
  for (const char* n : {"link_a1", "link_b2", "joint_a3", "joint_b1", "ee", "tip_b3", "motor_a2",
                        "close_b2", "close_b3"}) {
    EXPECT_NE(xml.find(std::string("name=\"") + n + "\""), std::string::npos) << n;
  }
  EXPECT_NE(xml.find("<compiler angle=\"radian\""), std::string::npos);
  EXPECT_NE(xml.find("<flag contact=\"disable\"/>"), std::string::npos);
  EXPECT_NE(xml.find("solref=\"0.001 1\""), std::string::npos);
  EXPECT_NE(xml.find("solimp=\"0.9999 0.9999 0.001\""), std::string::npos);
  EXPECT_EQ(std::count(xml.begin(), xml.end(), '\n') > 40, true);
}

TEST(Mjcf, OptionsReachTheText) {
  MjcfOptions o;
  o.timestep_s = 0.00025;
  o.armature_kg_m2 = 0.005;
  const std::string xml = mjcf_from_robot(Robot{}, o);
  EXPECT_NE(xml.find("timestep=\"0.00025\""), std::string::npos);
  EXPECT_EQ(attribute(xml, "joint_a2", "armature"), "0.005");
}

TEST(Mjcf, RefusesParametersThatCannotAssemble) {
  Robot r;
  r.geometry[kLa1] = 50.0;  // chain 1 reaches 50 to 150 mm; home is 216.5 mm from A1
  r.geometry[kLb1] = 100.0;
  try {
    mjcf_from_robot(r);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot assemble at home"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("chain 1"), std::string::npos) << e.what();
  }
}

TEST(Mjcf, EscapesTheModelName) {
  Robot r;
  r.name = "a<b>&\"c\"";
  EXPECT_NE(mjcf_from_robot(r).find("model=\"a&lt;b&gt;&amp;&quot;c&quot;\""), std::string::npos);
}

TEST(Mjcf, EffectsOffLeaveTheIdealModelAndOnAddTheirParts) {
  const std::string ideal = mjcf_from_robot(Robot{});
  for (const char* part : {"rotor_a", "joint_m", "clear_", "pin_b", "frictionloss", "stiffness"})
    EXPECT_EQ(ideal.find(part), std::string::npos) << part;
  MjcfOptions o;
  o.effects.compliance_rad_per_Nm = {1e-4, 0.0, 0.0};
  o.effects.coulomb_Nm = {0.0, 0.5, 0.0};
  o.effects.clearance_m = {0.0, 0.0, 5e-6};
  const std::string x = mjcf_from_robot(Robot{}, o);
  // Compliance on chain 1 only: the rotor (own body, the armature, the motor)
  // and the link, both absolute hinges at rest at the home angle, joined by a
  // twist tendon of stiffness 1 / compliance.
  EXPECT_NE(x.find("<body name=\"rotor_a1\""), std::string::npos);
  EXPECT_EQ(x.find("rotor_a2"), std::string::npos);
  EXPECT_TRUE(std::regex_search(x, std::regex(R"re(joint_m1" type="hinge" axis="0 0 1" ref="([-0-9.e]+)" springref="\1" damping="0.05" armature="0.0026")re")));
  EXPECT_TRUE(std::regex_search(x, std::regex(R"re(joint_a1" type="hinge" axis="0 0 1" ref="([-0-9.e]+)" springref="\1"/>)re")));
  EXPECT_TRUE(std::regex_search(x, std::regex(R"re(<fixed name="twist_a1" stiffness="10000">\s*<joint joint="joint_m1" coef="1"/>\s*<joint joint="joint_a1" coef="-1"/>)re")));
  EXPECT_EQ(x.find("twist_a2"), std::string::npos);
  EXPECT_NE(x.find(R"(<motor name="motor_a1" joint="joint_m1")"), std::string::npos);
  EXPECT_NE(x.find(R"(<motor name="motor_a2" joint="joint_a2")"), std::string::npos);
  EXPECT_NE(x.find(R"(joint_a2" type="hinge" axis="0 0 1" ref=)"), std::string::npos);
  EXPECT_NE(x.find(R"(frictionloss="0.5")"), std::string::npos);
  // Clearance 5 um on chain 3: its hub pin may sit anywhere within 2c = 10 um
  // of the passive link's tip (both pins' play): a tendon limited to that
  // length closes the loop instead of the connect; chain 2 keeps its connect.
  EXPECT_TRUE(std::regex_search(x, std::regex(R"re(<spatial name="clear_b3" limited="true" range="0 1e-05"[^>]*>\s*<site site="tip_b3"/>\s*<site site="ee"/>)re")));
  EXPECT_EQ(x.find("close_b3"), std::string::npos);
  // Its centring spring rests at length 0 (MuJoCo's default rest length is
  // not the home length), and the hub is held on the link's line by a tendon
  // equality on the tendon from a site 0.1 m across the tip to ee.
  EXPECT_TRUE(std::regex_search(x, std::regex(R"re(<spatial name="clear_b3"[^>]* springlength="0">)re")));
  EXPECT_NE(x.find(R"(<site name="side_b3" pos="0.244 0.1 0")"), std::string::npos);
  EXPECT_TRUE(std::regex_search(x, std::regex(R"re(<spatial name="side_b3">\s*<site site="side_b3"/>\s*<site site="ee"/>)re")));
  EXPECT_NE(x.find(R"(<tendon name="hold_b3" tendon1="side_b3"/>)"), std::string::npos);
  EXPECT_EQ(x.find("side_b2"), std::string::npos);
  EXPECT_NE(x.find(R"(<connect name="close_b2" body1="link_b2" body2="ee" anchor="0.244 0 0"/>)"), std::string::npos);
  EXPECT_EQ(x.find("clear_b1"), std::string::npos);
  EXPECT_EQ(x.find("clear_b2"), std::string::npos);
  EXPECT_EQ(x.find("pin_b"), std::string::npos);
  // Clearance on chain 1, which carries the hub: a slide along its passive
  // link with the play of both pins, +-2c.
  o.effects.clearance_m = {5e-6, 0.0, 0.0};
  const std::string x1 = mjcf_from_robot(Robot{}, o);
  EXPECT_NE(x1.find(R"(<joint name="clear_b1x" type="slide" axis="1 0 0" limited="true" range="-1e-05 1e-05")"),
            std::string::npos);
  EXPECT_NE(x1.find("<connect name=\"close_b3\""), std::string::npos);
  EXPECT_EQ(x1.find("<spatial"), std::string::npos);
}

// The drives' friction time constant: the default, 0, two physics steps (the
// stiffest MuJoCo allows); MuJoCo's own default writes no attribute, another
// value its solreffriction on every drive joint with friction.
TEST(Mjcf, FrictionTimeconstReachesTheDriveJoints) {
  MjcfOptions o;
  o.timestep_s = 0.00025;
  o.effects.compliance_rad_per_Nm = {1e-4, 0.0, 0.0};
  o.effects.coulomb_Nm = {0.3, 0.3, 0.0};
  EXPECT_EQ(attribute(mjcf_from_robot(Robot{}, o), "joint_m1", "solreffriction"), "0.0005 1");  // the default
  o.effects.friction_timeconst_s = kMujocoFrictionTimeconst;
  EXPECT_EQ(mjcf_from_robot(Robot{}, o).find("solreffriction"), std::string::npos);
  o.effects.friction_timeconst_s = 0.004;
  const std::string x = mjcf_from_robot(Robot{}, o);
  EXPECT_EQ(attribute(x, "joint_m1", "solreffriction"), "0.004 1");  // the rotor of a compliant drive
  EXPECT_EQ(attribute(x, "joint_a2", "solreffriction"), "0.004 1");  // a rigid drive
  EXPECT_EQ(attribute(x, "joint_a3", "solreffriction"), "<missing>");  // no friction on chain 3
}

TEST(Mjcf, TransmissionRateIsHookesLawOnTheTwoInertias) {
  MjcfOptions o;
  EXPECT_EQ(transmission_omega(o, 0, 0.244), 0.0);
  o.effects.compliance_rad_per_Nm.fill(1e-4);
  const double i_link = o.active_link_mass_kg * 0.244 * 0.244 / 3.0;
  EXPECT_NEAR(transmission_omega(o, 1, 0.244), std::sqrt(1e4 * (1.0 / 0.0026 + 1.0 / i_link)), 1e-9);
}

}  // namespace
}  // namespace gpm
