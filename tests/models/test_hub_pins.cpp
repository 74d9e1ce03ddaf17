// Tests of models/hub_pins.cpp (MJCF text and assembly; tests/sim/test_hub_pins.cpp
// compiles it with MuJoCo), against independent facts:
// - zero offsets: the MJCF is the committed nominal model, byte for byte,
//   and with other effects on it equals the text without the key;
// - the assembly angles put the tip of every passive link on its pin,
//   home + p_i (eq. 29-31 checked by the forward relation of eq. 30);
// - the 15-parameter forward kinematics of those angles misses the hub
//   centre by d, which to first order in p solves d . u_i - c = p_i . u_i
//   (u_i the unit vector from elbow B_i to the hub; the FK's radical centre
//   has equal power |X - B_i|^2 - lb_i^2 for the three circles, and the pin
//   on circle i is O + p_i); equal offsets p give d = p exactly (the common pin);
// - with offsets the MJCF has the hub's hinge and closes chains 2, 3 at pin sites.
#include "models/hub_pins.hpp"

#include <fstream>
#include <sstream>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "models/data_dir.hpp"

namespace gpm {
namespace {

MjcfOptions with_pins(const std::array<std::array<double, 2>, 3>& p_m) {
  MjcfOptions o;
  o.effects.hub_pin_m = p_m;
  return o;
}

const std::array<std::array<double, 2>, 3> kPins{{{8e-6, -3e-6}, {-5e-6, 12e-6}, {4e-6, 6e-6}}};

TEST(HubPins, ZeroOffsetsLeaveTheModelByteForByte) {
  std::ifstream in(models_dir() + "/gpm2002.xml", std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_EQ(mjcf_from_robot(Robot{}, with_pins({})), ss.str());
  MjcfOptions loose;
  loose.effects.clearance_m = {5e-6, 5e-6, 5e-6};
  loose.effects.compliance_rad_per_Nm = {1e-4, 1e-4, 1e-4};
  MjcfOptions loose_zero = loose;
  loose_zero.effects.hub_pin_m = {};
  EXPECT_EQ(mjcf_from_robot(Robot{}, loose_zero), mjcf_from_robot(Robot{}, loose));
  EXPECT_FALSE(loose.effects.pinned_hub());
}

TEST(HubPins, AssemblyPutsEveryLinkTipOnItsPin) {
  const Robot r;
  const MjcfEffects fx = with_pins(kPins).effects;
  const JointAngles q = hub_assembly_ik(r.geometry, r.home, r.branch, fx);
  const auto b = elbows(r.geometry, q.theta_a);
  for (int i = 0; i < kNumChains; ++i) {
    const Eigen::Vector2d tip = b[i] + r.geometry.lb_(i) * Eigen::Vector2d(std::cos(q.theta_b[i]), std::sin(q.theta_b[i]));
    const Eigen::Vector2d pin = r.home + Eigen::Vector2d(kPins[i][0], kPins[i][1]) * 1e3;  // mm
    EXPECT_LT((tip - pin).norm(), 1e-9) << "chain " << i + 1;
  }
}

// FK error d (mm) predicted to first order for pins p (mm) at angles q.
Eigen::Vector2d predicted_fk_error(const Robot& r, const JointAngles& q, const std::array<Eigen::Vector2d, 3>& p) {
  const auto b = elbows(r.geometry, q.theta_a);
  Eigen::Matrix3d a;
  Eigen::Vector3d rhs;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d u = (r.home - b[i]).normalized();
    a.row(i) << u.x(), u.y(), -1.0;
    rhs[i] = p[i].dot(u);
  }
  return a.lu().solve(rhs).head<2>();
}

TEST(HubPins, FifteenParameterKinematicsMissesTheHubCentreByThePredictedError) {
  const Robot r;
  const JointAngles q = hub_assembly_ik(r.geometry, r.home, r.branch, with_pins(kPins).effects);
  std::array<Eigen::Vector2d, 3> p_mm;
  double largest = 0.0;
  for (int i = 0; i < 3; ++i) p_mm[i] = Eigen::Vector2d(kPins[i][0], kPins[i][1]) * 1e3, largest = std::max(largest, p_mm[i].norm());
  const auto fk = forward_kinematics(r.geometry, q.theta_a);
  ASSERT_TRUE(fk.has_value());
  const Eigen::Vector2d d = fk->p - r.home;
  const Eigen::Vector2d want = predicted_fk_error(r, q, p_mm);
  EXPECT_GT(d.norm(), 0.1 * largest) << "the 15 parameters cannot hold the offsets";
  EXPECT_LT((d - want).norm(), 0.01 * want.norm()) << "d " << d.transpose() << " predicted " << want.transpose();
  // Equal offsets: one common pin at home + p, which the FK finds.
  const std::array<std::array<double, 2>, 3> same{{{7e-6, -4e-6}, {7e-6, -4e-6}, {7e-6, -4e-6}}};
  const JointAngles qs = hub_assembly_ik(r.geometry, r.home, r.branch, with_pins(same).effects);
  const Eigen::Vector2d ds = forward_kinematics(r.geometry, qs.theta_a)->p - r.home;
  EXPECT_LT((ds - Eigen::Vector2d(7e-3, -4e-3)).norm(), 1e-9);
}

TEST(HubPins, ModelHasTheHubHingeAndClosesAtThePins) {
  MjcfOptions o = with_pins(kPins);
  const std::string x = mjcf_from_robot(Robot{}, o);
  EXPECT_NE(x.find("<joint name=\"hub_r\""), std::string::npos);
  EXPECT_NE(x.find("<site name=\"pin_b2\""), std::string::npos);
  EXPECT_NE(x.find("<site name=\"pin_b3\""), std::string::npos);
  o.effects.clearance_m = {5e-6, 5e-6, 5e-6};
  const std::string loose = mjcf_from_robot(Robot{}, o);
  EXPECT_NE(loose.find("<site site=\"pin_b2\"/>"), std::string::npos) << "the clearance tendon ends at the pin";
  EXPECT_EQ(loose.find("<site site=\"ee\"/>"), std::string::npos);
}

}  // namespace
}  // namespace gpm
