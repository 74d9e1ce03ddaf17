// Tests of models/mjcf.cpp (text only; tests/sim/test_twin.cpp compiles the
// MJCF with MuJoCo and checks the loop closure): the committed nominal model
// equals the generator output, bodies sit at the IK of the actual parameters,
// millimetres become metres, and parameters that cannot assemble are refused.
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

}  // namespace
}  // namespace gpm
