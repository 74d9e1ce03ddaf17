// Tests of calib/friction_profile.cpp: readings of passive links at the end
// of their axial play by the sign of their force, that force from the drive
// torque less a Coulomb friction F (virtual work, independent of the
// calibration's formula); a calibration told 2F or F/2 picks the factor that
// gives back F (the smallest chi2/dof), and there recovers the plays within
// 4 sigma; a friction that builds up over 0.3 rad/s is found by the speed
// profile; a walk from a start chooses what fitting every value chooses, in
// fewer fits (every value where its minimum is above the trust), and takes a
// known fit as it is; bad arguments are refused; a speed whose twist is the
// latch skew's column over the joints' speeds is not tried (a hand-worked
// correlation).
#include "calib/friction_profile.hpp"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "calib/paper_values.hpp"
#include "calib/synthetic.hpp"
#include "models/errors.hpp"
#include "models/kinematics.hpp"
#include "models/rng.hpp"

namespace gpm::calib {
namespace {

constexpr double kSigma = 1e-5;
constexpr double kFriction_Nm = 1.0;
const std::array<double, 3> kPlay = {0.010, 0.008, 0.012};  // mm
const Eigen::Vector3d kCompliance(1.0e-4, 1.2e-4, 0.8e-4);   // rad/N m

struct PlayData {
  Problem problem;
  std::vector<Eigen::Vector3d> omega, tau;
  Geometry truth;
};

// 800 samples of the Table-5 robot, drive torques ~ N(0, 1.5 N m) and speeds
// ~ N(0, 1 rad/s); link i is lb_i + d_i sign(T_i), T_i from the transmitted
// torque tau_i - F tanh(omega_i / speed); readings by IK of that
// geometry, twisted by c_i (tau_i - F tanh(...)), plus noise.
PlayData make_play_data(double speed = kFrictionSpeed) {
  Robot a;
  a.geometry = table5_actual();
  const std::vector<Eigen::Vector2d> poses = disc_poses(a, 800, a.home, 100.0, 41);
  PlayData d;
  d.truth = a.geometry;
  d.problem.start = Robot{}.geometry;
  for (int k : {kXa1, kYa1, kXa2, kYa2}) d.problem.start.values[k] = a.geometry.values[k];
  d.problem.free = default_free_mask();
  Rng rng(42);
  for (const Eigen::Vector2d& p : poses) {
    const Eigen::Vector3d w(rng.normal(0, 1.0), rng.normal(0, 1.0), rng.normal(0, 1.0));
    const Eigen::Vector3d t(rng.normal(0, 1.5), rng.normal(0, 1.5), rng.normal(0, 1.5));
    const JointAngles q = inverse_kinematics(a.geometry, p);
    Geometry gj = a.geometry;
    Eigen::Vector3d carried;
    for (int i = 0; i < 3; ++i) {
      carried[i] = t[i] - kFriction_Nm * std::tanh(w[i] / speed);
      const Eigen::Vector2d A(a.geometry[xa(i)], a.geometry[ya(i)]);
      const auto dist = [&](double th) {
        return (p - A - a.geometry.la_(i) * Eigen::Vector2d(std::cos(th), std::sin(th))).norm();
      };
      const double tension = carried[i] / (1e-3 * (dist(q.theta_a[i] + 1e-6) - dist(q.theta_a[i] - 1e-6)) / 2e-6);
      gj.values[lb(i)] += (tension > 0.0 ? 1.0 : -1.0) * kPlay[static_cast<std::size_t>(i)];
    }
    const JointAngles qj = inverse_kinematics(gj, p);
    const Eigen::Vector3d noise(rng.normal(0, kSigma), rng.normal(0, kSigma), rng.normal(0, kSigma));
    d.omega.push_back(w);
    d.tau.push_back(t);
    d.problem.theta_m.push_back(readings_from_active(gj, qj.theta_a) + noise + kCompliance.cwiseProduct(carried));
  }
  return d;
}

MotionModel stated(double coulomb_Nm) {
  MotionModel m;
  m.skew = false;
  m.clearance = true;
  m.load.coulomb_Nm.fill(coulomb_Nm);
  return m;
}

TEST(FrictionProfile, PicksTheFactorThatGivesBackTheFriction) {
  const PlayData d = make_play_data();
  LmOptions o;
  o.encoder_sigma = kSigma;
  const std::vector<double> scales = {0.25, 0.5, 1.0, 2.0, 4.0};
  for (double told : {2.0 * kFriction_Nm, 0.5 * kFriction_Nm}) {
    const FrictionProfile p = calibrate_friction_profile(d.problem, d.omega, d.tau, o, stated(told), {}, scales, kSigma);
    EXPECT_DOUBLE_EQ(p.scale * told, kFriction_Nm) << "told " << told;
    EXPECT_DOUBLE_EQ(p.model.load.coulomb_Nm[1], kFriction_Nm);
    ASSERT_EQ(p.chi2_per_dof.size(), scales.size());
    const double best = *std::min_element(p.chi2_per_dof.begin(), p.chi2_per_dof.end());
    for (std::size_t k = 0; k < scales.size(); ++k)
      if (scales[k] != p.scale) {
        EXPECT_GT(p.chi2_per_dof[k], best) << "factor " << scales[k];
      }
    for (std::size_t i = 0; i < 3; ++i) {
      ASSERT_TRUE(std::isfinite(p.fit.clearance_sigma[i]));
      EXPECT_LT(std::abs(p.fit.clearance[i] - kPlay[i]), 4.0 * p.fit.clearance_sigma[i]) << "play of chain " << i + 1;
    }
  }
  // Told the truth, the wrong factors fit worse by a margin (the model test tells them apart).
  const FrictionProfile truth = calibrate_friction_profile(d.problem, d.omega, d.tau, o, stated(kFriction_Nm), {}, scales, kSigma);
  EXPECT_EQ(truth.scale, 1.0);
  EXPECT_GT(truth.chi2_per_dof[4], 1.5 * truth.chi2_per_dof[2]);  // 4x the friction
}

TEST(FrictionProfile, SpeedProfilePicksTheSpeedOverWhichTheFrictionBuildsUp) {
  constexpr double kSpeed = 0.3;  // rad/s; the joint speeds are ~ N(0, 1 rad/s): a third of the samples within it
  const PlayData d = make_play_data(kSpeed);
  LmOptions o;
  o.encoder_sigma = kSigma;
  const std::vector<double> speeds = {0.01, 0.1, kSpeed, 1.0};
  MotionModel m = stated(kFriction_Nm);
  const FrictionProfile p = friction_speed_profile(d.problem, d.omega, d.tau, o, m, {}, speeds, kSigma);
  EXPECT_EQ(p.scale, kSpeed);
  EXPECT_EQ(p.model.load.friction_speed_rad_s, kSpeed);
  EXPECT_EQ(p.model.load.coulomb_Nm[0], kFriction_Nm);  // the friction itself untouched
  ASSERT_EQ(p.chi2_per_dof.size(), speeds.size());
  // The step of the old default fits worse by a margin, and the true speed's fit passes for noise.
  EXPECT_GT(p.chi2_per_dof[0], 1.2 * p.chi2_per_dof[2]);
  EXPECT_LT(p.chi2_per_dof[2], 1.15);
  // There the friction twist c_i F comes back within 4 sigma.
  for (std::size_t i = 0; i < 3; ++i) {
    ASSERT_TRUE(std::isfinite(p.fit.friction_sigma[i]));
    EXPECT_LT(std::abs(p.fit.friction[i] - kCompliance[static_cast<Eigen::Index>(i)] * kFriction_Nm),
              4.0 * p.fit.friction_sigma[i])
        << "friction twist of joint " << i + 1;
  }
}

TEST(FrictionProfile, WalkFromAStartChoosesWhatTheWholeGridChooses) {
  const PlayData d = make_play_data();
  LmOptions o;
  o.encoder_sigma = kSigma;
  const std::vector<double> scales = {0.25, 0.5, 1.0, 2.0, 4.0};
  // From the stated factor and from below (far above, at 4x, chi2/dof falls
  // again: a walk starts at the stated value, as the procedure's does).
  for (double from : {1.0, 0.25}) {
    const FrictionProfile all = calibrate_friction_profile(d.problem, d.omega, d.tau, o, stated(2.0 * kFriction_Nm), {},
                                                           scales, kSigma);
    const FrictionProfile walk = calibrate_friction_profile(d.problem, d.omega, d.tau, o, stated(2.0 * kFriction_Nm),
                                                            {}, scales, kSigma, ProfileStart{from, nullptr, true});
    EXPECT_EQ(walk.scale, all.scale) << "from " << from;
    EXPECT_EQ(walk.fit.result.geometry.values, all.fit.result.geometry.values) << "from " << from;
    ASSERT_EQ(walk.scales.size(), walk.chi2_per_dof.size());
    EXPECT_TRUE(std::is_sorted(walk.scales.begin(), walk.scales.end()));
    for (std::size_t k = 0; k < walk.scales.size(); ++k) {  // each tried value's chi2/dof as the whole grid's
      const auto at = std::find(scales.begin(), scales.end(), walk.scales[k]) - scales.begin();
      EXPECT_EQ(walk.chi2_per_dof[k], all.chi2_per_dof[static_cast<std::size_t>(at)]);
    }
    // From next to the minimum 0.5: the start, its neighbours and the minimum's other neighbour.
    if (from == 1.0) {
      EXPECT_EQ(walk.scales, (std::vector<double>{0.25, 0.5, 1.0, 2.0}));
    }
  }
  // A minimum above the trust: every value fitted after all.
  ProfileStart distrust{1.0, nullptr, true};
  distrust.trust = 0.0;
  EXPECT_EQ(calibrate_friction_profile(d.problem, d.omega, d.tau, o, stated(2.0 * kFriction_Nm), {}, scales, kSigma,
                                       distrust).scales,
            scales);
  // A known fit at the start is taken as it is, not made again: a fit made
  // at another factor gives the start that factor's chi2/dof.
  const FrictionProfile at4 = calibrate_friction_profile(d.problem, d.omega, d.tau, o, stated(2.0 * kFriction_Nm), {},
                                                         {4.0}, kSigma);
  const FrictionProfile walk = calibrate_friction_profile(d.problem, d.omega, d.tau, o, stated(2.0 * kFriction_Nm), {},
                                                          scales, kSigma, ProfileStart{1.0, &at4.fit, true});
  EXPECT_EQ(walk.chi2_per_dof[std::find(walk.scales.begin(), walk.scales.end(), 1.0) - walk.scales.begin()],
            at4.chi2_per_dof[0]);
  // Without a walk every value is fitted but the known one; the speed profile alike.
  const std::vector<double> speeds = default_friction_speeds();
  const FrictionProfile sp_all = friction_speed_profile(d.problem, d.omega, d.tau, o, stated(kFriction_Nm), {}, speeds, kSigma);
  MotionModel at_speed = stated(kFriction_Nm);
  at_speed.load.friction_speed_rad_s = speeds[2];
  const FrictionProfile sp_known = friction_speed_profile(d.problem, d.omega, d.tau, o, at_speed, {}, speeds, kSigma,
                                                          ProfileStart{speeds[2], &at4.fit});
  EXPECT_EQ(sp_known.scales, speeds);
  for (std::size_t k = 0; k < speeds.size(); ++k)
    EXPECT_EQ(sp_known.chi2_per_dof[k], k == 2 ? at4.chi2_per_dof[0] : sp_all.chi2_per_dof[k]) << "speed " << speeds[k];
}

TEST(FrictionProfile, RefusesBadArguments) {
  const PlayData d = make_play_data();
  LmOptions o;
  o.encoder_sigma = kSigma;
  EXPECT_THROW(calibrate_friction_profile(d.problem, d.omega, d.tau, o, stated(1.0), {}, {}, kSigma), InputError);
  EXPECT_THROW(calibrate_friction_profile(d.problem, d.omega, d.tau, o, stated(1.0), {}, {1.0, -0.5}, kSigma), InputError);
  EXPECT_THROW(calibrate_friction_profile(d.problem, d.omega, d.tau, o, stated(1.0), {}, {1.0}, 0.0), InputError);
  // A start that is not a value of the grid, or a grid not ascending to walk along.
  EXPECT_THROW(calibrate_friction_profile(d.problem, d.omega, d.tau, o, stated(1.0), {}, {0.5, 1.0}, kSigma,
                                          ProfileStart{0.7, nullptr, true}),
               InputError);
  EXPECT_THROW(calibrate_friction_profile(d.problem, d.omega, d.tau, o, stated(1.0), {}, {1.0, 0.5}, kSigma,
                                          ProfileStart{1.0, nullptr, true}),
               InputError);
  EXPECT_THROW(calibrate_friction_profile(d.problem, d.omega, d.tau, o, stated(1.0), {}, {0.5, 1.0}, kSigma,
                                          ProfileStart{std::nullopt, nullptr, true}),
               InputError);
  EXPECT_THROW(friction_speed_profile(d.problem, d.omega, d.tau, o, stated(1.0), {}, {}, kSigma), InputError);
  EXPECT_THROW(friction_speed_profile(d.problem, d.omega, d.tau, o, stated(1.0), {}, {0.1, 0.0}, kSigma), InputError);
  EXPECT_THROW(friction_speed_profile(d.problem, d.omega, d.tau, o, stated(1.0), {}, {0.1}, 0.0), InputError);
  const std::vector<double> v = default_friction_speeds();
  ASSERT_EQ(v.size(), 5u);
  EXPECT_DOUBLE_EQ(v.front(), 0.01);
  EXPECT_DOUBLE_EQ(v.back(), 1.0);
  EXPECT_DOUBLE_EQ(v[1] / v[0], std::sqrt(10.0));
  const std::vector<double> g = default_friction_scales();
  ASSERT_EQ(g.size(), 10u);
  EXPECT_EQ(g.front(), 0.0);
  EXPECT_DOUBLE_EQ(g[1], 0.25);
  EXPECT_DOUBLE_EQ(g[5], 1.0);
  EXPECT_DOUBLE_EQ(g.back(), 4.0);
  EXPECT_DOUBLE_EQ(g[6] / g[5], std::sqrt(2.0));
}

// Joint speeds spread evenly over [-1, 1] rad/s on joints 2 and 3 (joint 1 at rest).
std::vector<Eigen::Vector3d> even_speeds() {
  std::vector<Eigen::Vector3d> w;
  for (int j = 0; j <= 2000; ++j) w.emplace_back(0.0, -1.0 + 1e-3 * j, 1.0 - 1e-3 * j);
  return w;
}

TEST(FrictionProfile, SpeedsTheSkewCannotTellFromTheTwistAreNotTried) {
  const std::vector<Eigen::Vector3d> w = even_speeds();
  const std::array<bool, 3> skewed{false, true, true};
  // Far above the joints' speeds the twist tanh(omega / v) is linear in omega,
  // the skew's column (correlation 1 - 1e-5 at v = 10); far below them it is
  // sign(omega), whose correlation with omega uniform on [-a, a] is
  // E|omega| / sqrt(E omega^2) = (a / 2) / (a / sqrt 3) = sqrt(3) / 2 = 0.866.
  EXPECT_EQ(speeds_told_from_skew({1e-4, 10.0}, w, skewed), (std::vector<double>{1e-4}));
  EXPECT_EQ(speeds_told_from_skew({1e-4, 10.0}, w, skewed, 0.87), (std::vector<double>{1e-4}));
  // Below sqrt(3) / 2 no speed qualifies: the smallest stays.
  EXPECT_EQ(speeds_told_from_skew({10.0, 1e-4, 1.0}, w, skewed, 0.86), (std::vector<double>{1e-4}));
  // Without a skew, or without motion, every speed is tried.
  EXPECT_EQ(speeds_told_from_skew({1e-4, 10.0}, w, {true, false, false}), (std::vector<double>{1e-4, 10.0}));
  const std::vector<Eigen::Vector3d> rest(10, Eigen::Vector3d::Zero());
  EXPECT_EQ(speeds_told_from_skew({1e-4, 10.0}, rest, skewed), (std::vector<double>{1e-4, 10.0}));
  // The default grid on these speeds (up to 1 rad/s): 0.316 and 1 rad/s are the skew's column.
  EXPECT_EQ(speeds_told_from_skew(default_friction_speeds(), w, skewed).size(), 3u);
}

}  // namespace
}  // namespace gpm::calib
