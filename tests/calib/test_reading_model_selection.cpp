// Tests of calib/reading_model_selection.cpp (and the drive-train columns and
// the sandwich covariance of calib/motion_correction.cpp it relies on):
// readings generated with a backlash on two joints and a harmonic error once
// per motor revolution on one (geared 10:1) give back those effects, within
// their 1-sigma, and drop the candidates the robot does not have; the
// geometry comes back within its 1-sigma, where the fit without the drive
// train is far off; the sandwich covariance of a fit that leaves an effect
// out covers its error, where the noise model's does not; on white noise the
// sandwich is not taken; with none kept, a fit without them already made is
// taken as it is; the harmonic candidates join a model without its backlash;
// two backlashes whose flanks are certain together in a third of the samples
// are both estimated; a candidates' fit that diverges leaves them out;
// readings with a reducer hysteresis on two joints along a path give back
// its loss and the geometry, a joint whose mesh torque is too small to slide
// the element is no candidate, and a robot without it keeps none; a motor's
// cogging (24 periods per motor revolution) is kept on the joint that has it
// and on no other.
#include "calib/reading_model_selection.hpp"

#include <array>
#include <cmath>

#include <gtest/gtest.h>

#include "calib/paper_values.hpp"
#include "calib/passive_tension.hpp"
#include "calib/synthetic.hpp"
#include "models/errors.hpp"
#include "models/rng.hpp"

namespace gpm::calib {
namespace {

constexpr double kSigma = 2e-6;
constexpr double kGear = 10.0;
const Eigen::Vector3d kBeta(0.0, 4e-4, 2.5e-4);             // half lost motion per joint (rad)
const Eigen::Vector3d kMotorSin(3e-5, 0.0, 0.0), kMotorCos(-2e-5, 0.0, 0.0);  // once per motor revolution
constexpr double kCoggingPeriods = 24.0;
const Eigen::Vector3d kCogging(0.0, 0.0, 1.5e-5);  // a sin(P N theta_m): the cogging's twist on joint 3

struct DriveData {
  Problem problem;
  std::vector<Eigen::Vector3d> omega, tau;
  Geometry truth;
};

// n samples of the Table-5 robot with random speeds and torques whose readings
// carry the drive train: theta_m = theta + beta sgn(tau) + a sin(N theta_m) + b cos(N theta_m)
// (the correction of calib/motion_correction.hpp inverted, by fixed point);
// with_drive false: the readings theta alone.
DriveData make_data(int n, std::uint64_t seed, bool with_drive = true, bool along_path = false, bool cogging = false) {
  Robot a;
  a.geometry = table5_actual();
  std::vector<Eigen::Vector2d> poses = disc_poses(a, n, a.home, 100.0, seed);
  if (along_path)  // consecutive samples of one smooth path (a rosette round home), as on the fly
    for (int j = 0; j < n; ++j) {
      const double u = 2.0 * M_PI * j / n, radius = 60.0 + 30.0 * std::sin(3.0 * u);
      poses[static_cast<std::size_t>(j)] = a.home + radius * Eigen::Vector2d(std::cos(5.0 * u), std::sin(5.0 * u));
    }
  const Samples smp = samples_at(a, poses, kSigma, seed + 1);
  DriveData d;
  d.truth = a.geometry;
  Rng rng(seed + 2);
  for (std::size_t j = 0; j < smp.size(); ++j) {
    d.omega.emplace_back(rng.normal(0, 1.0), rng.normal(0, 1.0), rng.normal(0, 1.0));
    d.tau.emplace_back(rng.normal(0, 3.0), rng.normal(0, 3.0), rng.normal(0, 3.0));
    Eigen::Vector3d m = smp.theta_m[j];
    for (int it = 0; it < 20 && with_drive; ++it)
      for (int i = 0; i < 3; ++i)
        m[i] = smp.theta_m[j][i] + kBeta[i] * (d.tau.back()[i] > 0 ? 1.0 : -1.0) + kMotorSin[i] * std::sin(kGear * m[i]) +
               kMotorCos[i] * std::cos(kGear * m[i]) +
               (cogging ? kCogging[i] * std::sin(kCoggingPeriods * kGear * m[i]) : 0.0);
    d.problem.theta_m.push_back(m);
  }
  d.problem.start = Robot{}.geometry;
  for (int k : {kXa1, kYa1, kXa2, kYa2}) d.problem.start.values[k] = a.geometry.values[k];
  d.problem.free = default_free_mask();
  return d;
}

// A rigid reading model (no skew, compliance or friction) on a 10:1 drive.
MotionModel rigid_geared() {
  MotionModel m;
  m.skew = m.compliance = m.friction = false;
  m.gear_ratio = kGear;
  m.backlash_torque_min_Nm = 0.05;
  return m;
}

// Every drive-train candidate on every joint.
MotionModel every_candidate() {
  MotionModel c;
  c.backlash = c.joint_harmonic = c.motor_harmonic1 = c.motor_harmonic2 = {true, true, true};
  return c;
}

// The largest error of the free parameters of r against truth, in r's 1-sigma.
double worst_in_sigmas(const DriveData& d, const Result& r) {
  double w = 0.0;
  for (int k = 0; k < kNumParams; ++k)
    if (d.problem.free[k]) w = std::max(w, std::abs(r.geometry.values[k] - d.truth.values[k]) / r.sigma[k]);
  return w;
}

TEST(ReadingModelSelection, KeepsTheDriveEffectsTheRobotHasAndDropsTheOthers) {
  const DriveData d = make_data(800, 7);
  LmOptions o;
  o.encoder_sigma = kSigma;
  const DriveEffectSelection s =
      select_drive_effects(d.problem, d.omega, d.tau, o, rigid_geared(), {}, every_candidate());
  EXPECT_FALSE(s.model.backlash[0]);
  EXPECT_TRUE(s.model.backlash[1]);
  EXPECT_TRUE(s.model.backlash[2]);
  EXPECT_TRUE(s.model.motor_harmonic1[0]);
  EXPECT_FALSE(s.model.motor_harmonic1[1]);
  EXPECT_FALSE(s.model.motor_harmonic2[0]);
  for (std::size_t i : {1u, 2u})
    EXPECT_LT(std::abs(s.fit.backlash[i] - kBeta[static_cast<Eigen::Index>(i)]), 4.0 * s.fit.backlash_sigma[i]);
  EXPECT_LT(std::abs(s.fit.harmonic[1][0] - kMotorSin[0]), 4.0 * s.fit.harmonic_sigma[1][0]);
  EXPECT_LT(std::abs(s.fit.harmonic[1][3] - kMotorCos[0]), 4.0 * s.fit.harmonic_sigma[1][3]);
  EXPECT_LT(worst_in_sigmas(d, s.fit.result), 4.0);
  EXPECT_FALSE(s.fit.sandwich_used);  // the model holds: the noise model's covariance
  // Without the drive train the same readings calibrate far from the truth.
  const MotionFit blind = calibrate_in_motion(d.problem, d.omega, d.tau, o, rigid_geared());
  EXPECT_GT(worst_in_sigmas(d, blind.result), 20.0);
}

// A joint whose mesh carries next to no torque (an unloaded, torque-off
// drive on a robot of little friction) cannot tell its flank: its backlash
// is no candidate (samples would all be left out) and the fit goes on.
TEST(ReadingModelSelection, ABacklashWhoseFlankTheSamplesCannotTellIsNoCandidate) {
  DriveData d = make_data(600, 17, false);
  Rng rng(18);
  for (Eigen::Vector3d& t : d.tau) t[0] = rng.normal(0.0, 0.01);  // joint 1: |tau| < 0.05 N m nearly always
  LmOptions o;
  o.encoder_sigma = kSigma;
  const DriveEffectSelection s =
      select_drive_effects(d.problem, d.omega, d.tau, o, rigid_geared(), {}, every_candidate());
  EXPECT_FALSE(s.model.backlash[0]);
  ASSERT_FALSE(s.dropped.empty());
  EXPECT_NE(s.dropped.front().find("backlash of joint 1"), std::string::npos) << s.dropped.front();
  EXPECT_GT(s.fit.kept.size(), 500u);  // joints 2 and 3 tell theirs in nearly every sample
  EXPECT_LT(worst_in_sigmas(d, s.fit.result), 4.0);
}

// select_drive_effects of d: every candidate on the rigid geared model, at the noise kSigma.
DriveEffectSelection select_every(const DriveData& d) {
  LmOptions o;
  o.encoder_sigma = kSigma;
  return select_drive_effects(d.problem, d.omega, d.tau, o, rigid_geared(), {}, every_candidate());
}

// n samples of make_data whose joints 2 and 3 each have their mesh torque
// in doubt (0.01 N m, its sign kept) in 40 % of the samples, at random.
DriveData flanks_in_doubt(int n) {
  DriveData d = make_data(n, 27);
  Rng rng(28);
  for (Eigen::Vector3d& t : d.tau)
    for (int i : {1, 2})
      if (rng.uniform(0.0, 1.0) < 0.4) t[i] = (t[i] > 0.0 ? 1.0 : -1.0) * 0.01;
  return d;
}

// Two joints whose flanks are each in doubt in 40 % of the samples, at
// different times: together certain in about a third of them, which is
// enough to estimate both lost motions (rather than leave one out).
TEST(ReadingModelSelection, KeepsTwoBacklashesWhoseFlanksAreCertainTogetherInAThird) {
  const DriveData d = flanks_in_doubt(1500);
  const DriveEffectSelection s = select_every(d);
  EXPECT_TRUE(s.model.backlash[1]);
  EXPECT_TRUE(s.model.backlash[2]);
  EXPECT_NEAR(static_cast<double>(s.fit.kept.size()) / 1500.0, 0.36, 0.05);  // 0.6 x 0.6 of them
  for (std::size_t i : {1u, 2u})
    EXPECT_LT(std::abs(s.fit.backlash[i] - kBeta[static_cast<Eigen::Index>(i)]), 4.0 * s.fit.backlash_sigma[i]);
  EXPECT_LT(worst_in_sigmas(d, s.fit.result), 4.0);
}

// A backlash the candidates lack (its flank in doubt) whose misfit the
// harmonics chase: their fit diverges, and the selection keeps the model
// without them, saying so, rather than failing the calibration.
TEST(ReadingModelSelection, ACandidateFitThatDivergesLeavesTheCandidatesOut) {
  const DriveData d = flanks_in_doubt(1500);
  LmOptions o;
  o.encoder_sigma = kSigma;
  MotionModel harmonics_only = every_candidate();
  harmonics_only.backlash = {};
  EXPECT_THROW(calibrate_in_motion(d.problem, d.omega, d.tau, o, with_harmonic_candidates(rigid_geared(), harmonics_only)),
               InputError) << "the case: the candidates' own fit diverges";
  const MotionFit plain = calibrate_in_motion(d.problem, d.omega, d.tau, o, rigid_geared());
  const DriveEffectSelection s =
      select_drive_effects(d.problem, d.omega, d.tau, o, rigid_geared(), {}, harmonics_only, 3.0, &plain);
  EXPECT_EQ(s.model.motor_harmonic1, (std::array<bool, 3>{}));
  EXPECT_EQ(s.model.joint_harmonic, (std::array<bool, 3>{}));
  ASSERT_EQ(s.dropped.size(), 1u);
  EXPECT_NE(s.dropped.front().find("diverged"), std::string::npos) << s.dropped.front();
  EXPECT_EQ(s.fit.result.geometry.values, plain.result.geometry.values);
}

TEST(ReadingModelSelection, FindsNothingOnARobotWithoutADriveTrain) {
  const DriveData d = make_data(600, 9, false);
  LmOptions o;
  o.encoder_sigma = kSigma;
  const DriveEffectSelection s =
      select_drive_effects(d.problem, d.omega, d.tau, o, rigid_geared(), {}, every_candidate());
  EXPECT_TRUE(s.kept.size() <= 1u) << "of 12 candidates at 3 sigma, at most one by chance";
  EXPECT_EQ(s.kept.size() + s.dropped.size(), 12u);
  EXPECT_LT(worst_in_sigmas(d, s.fit.result), 4.0);
  // None kept: given the fit without the drive train, that fit is the result,
  // bit for bit the one made again, and it is taken, not made (a fit of
  // another model given in its place comes back).
  ASSERT_TRUE(s.kept.empty());
  const MotionFit plain = calibrate_in_motion(d.problem, d.omega, d.tau, o, rigid_geared(), {});
  const DriveEffectSelection given =
      select_drive_effects(d.problem, d.omega, d.tau, o, rigid_geared(), {}, every_candidate(), 3.0, &plain);
  EXPECT_EQ(given.fit.result.geometry.values, s.fit.result.geometry.values);
  EXPECT_EQ(given.fit.chi2_per_dof, s.fit.chi2_per_dof);
  MotionFit other = plain;
  other.result.geometry.values[kLa1] += 1.0;
  EXPECT_EQ(select_drive_effects(d.problem, d.omega, d.tau, o, rigid_geared(), {}, every_candidate(), 3.0, &other)
                .fit.result.geometry.values,
            other.result.geometry.values);
}

// Along a path what the model leaves out is a smooth misfit: the sandwich's
// bandwidth follows its autocorrelation. (Of independent poses in random
// order a left-out effect is a bias no sandwich states.)
TEST(ReadingModelSelection, TheSandwichCoversWhatTheModelLeavesOutAlongAPath) {
  const DriveData d = make_data(2000, 13, true, true);
  LmOptions o;
  o.encoder_sigma = kSigma;
  MotionModel partial = rigid_geared();
  partial.backlash = {false, true, true};  // the motor harmonic of joint 1 left out
  MotionModel noise_only = partial;
  noise_only.sandwich = false;
  const MotionFit fit = calibrate_in_motion(d.problem, d.omega, d.tau, o, partial);
  const MotionFit naive = calibrate_in_motion(d.problem, d.omega, d.tau, o, noise_only);
  ASSERT_TRUE(fit.sandwich_used);
  EXPECT_GT(fit.chi2_per_dof, 2.0);
  EXPECT_GT(fit.sandwich_inflation, 1.5);
  EXPECT_FALSE(naive.sandwich_used);
  for (int k = 0; k < kNumParams; ++k) EXPECT_EQ(fit.result.geometry.values[k], naive.result.geometry.values[k]);
  // The noise model's 1-sigma misses the error by two orders (135 sigma when
  // written); the sandwich's holds it within the goal's 5 (4.9: the part of
  // the left-out effect the geometry absorbed leaves no residual to show it).
  EXPECT_GT(worst_in_sigmas(d, naive.result), 50.0);
  EXPECT_LT(worst_in_sigmas(d, fit.result), 5.0);
}

TEST(ReadingModelSelection, KeepsTheCoggingOfTheMotorThatCogs) {
  const DriveData d = make_data(800, 7, true, false, true);
  LmOptions o;
  o.encoder_sigma = kSigma;
  MotionModel model = rigid_geared(), candidates = every_candidate();
  model.cogging_periods = kCoggingPeriods;
  candidates.cogging = {true, true, true};
  const DriveEffectSelection s = select_drive_effects(d.problem, d.omega, d.tau, o, model, {}, candidates);
  EXPECT_EQ(s.model.cogging, (std::array<bool, 3>{false, false, true}));
  EXPECT_LT(std::abs(s.fit.harmonic[kCoggingHarmonic][2] - kCogging[2]), 4.0 * s.fit.harmonic_sigma[kCoggingHarmonic][2]);
  EXPECT_LT(std::abs(s.fit.harmonic[kCoggingHarmonic][5]), 4.0 * s.fit.harmonic_sigma[kCoggingHarmonic][5]);
  EXPECT_TRUE(s.model.backlash[1]);  // the rest of the drive train as without the cogging
  EXPECT_TRUE(s.model.motor_harmonic1[0]);
  EXPECT_LT(worst_in_sigmas(d, s.fit.result), 4.0);
  // Left out, the cogging costs the geometry.
  const DriveEffectSelection blind = select_drive_effects(d.problem, d.omega, d.tau, o, rigid_geared(), {}, every_candidate());
  EXPECT_GT(worst_in_sigmas(d, blind.fit.result), worst_in_sigmas(d, s.fit.result));
}

// The harmonic candidates join what the model has, and only those: the
// backlash stays the model's, and the model's own harmonics are kept.
TEST(ReadingModelSelection, HarmonicCandidatesJoinTheModelAndLeaveTheBacklash) {
  MotionModel model, candidates;
  model.motor_harmonic2 = {false, false, true};
  candidates.backlash = {true, true, true};
  candidates.joint_harmonic = {true, false, false};
  candidates.motor_harmonic1 = {false, true, false};
  candidates.motor_harmonic2 = {true, false, false};
  const MotionModel m = with_harmonic_candidates(model, candidates);
  EXPECT_EQ(m.backlash, (std::array<bool, 3>{false, false, false}));
  EXPECT_EQ(m.joint_harmonic, (std::array<bool, 3>{true, false, false}));
  EXPECT_EQ(m.motor_harmonic1, (std::array<bool, 3>{false, true, false}));
  EXPECT_EQ(m.motor_harmonic2, (std::array<bool, 3>{true, false, true}));
}

TEST(ReadingModelSelection, MeshTorqueIsTheDriveTorqueLessFrictionAndRotorInertia) {
  TransmissionLoad load;
  load.coulomb_Nm = {0.3, 0.3, 0.3};
  load.viscous_Nm_s = {0.1, 0.1, 0.1};
  load.rotor_inertia_kg_m2 = {0.002, 0.002, 0.002};
  load.inertia_kg_m2 = {0.05, 0.05, 0.05};  // the link's: not the mesh's load
  load.friction_speed_rad_s = 0.0;
  EXPECT_DOUBLE_EQ(mesh_torque(load, 1, 2.0, 0.5, 10.0), 2.0 - 0.3 - 0.05 - 0.02);
  EXPECT_DOUBLE_EQ(mesh_torque(load, 1, 2.0, -0.5, 0.0), 2.0 + 0.3 + 0.05);
  // Over a series, each sample's and joint's; no accelerations: none.
  const std::vector<Eigen::Vector3d> omega{{0.5, -0.5, 0.0}}, tau{{2.0, 2.0, 1.0}};
  const std::vector<Eigen::Vector3d> with_alpha = mesh_torques(load, omega, tau, {{10.0, 0.0, 0.0}});
  EXPECT_DOUBLE_EQ(with_alpha[0][0], 2.0 - 0.3 - 0.05 - 0.02);
  EXPECT_DOUBLE_EQ(mesh_torques(load, omega, tau, {})[0][1], 2.0 + 0.3 + 0.05);
  EXPECT_DOUBLE_EQ(with_alpha[0][2], 1.0);  // at rest: the friction's sign is 0
}

// Readings along a path whose joints 2 and 3 carry smooth torques through a
// reducer with hysteresis: theta_m = theta - eta g(tau; eta / c) (the
// correction of calib/motion_correction.hpp inverted), at compliance c the
// model's; joint 1's torque stays within 0.3 N m.
DriveData hysteresis_data(int n, std::uint64_t seed, const Eigen::Vector3d& eta, double c) {
  DriveData d = make_data(n, seed, false, true);
  for (int j = 0; j < n; ++j) {
    const double u = 2.0 * M_PI * j / n;
    d.tau[static_cast<std::size_t>(j)] = {0.3 * std::sin(7.0 * u), 3.0 * std::sin(4.0 * u) + 1.0 * std::sin(11.0 * u),
                                          2.5 * std::cos(5.0 * u) - 1.2 * std::sin(13.0 * u)};
  }
  for (int i = 0; i < 3; ++i) {
    std::vector<double> t;
    for (const Eigen::Vector3d& v : d.tau) t.push_back(v[i]);
    const std::vector<double> g = hysteresis_state(t, eta[i] / c);
    for (std::size_t j = 0; j < t.size(); ++j) d.problem.theta_m[j][i] -= eta[i] * g[j];
  }
  for (Eigen::Vector3d& w : d.omega) w.setZero();  // the mesh torque is the drive's (no friction)
  return d;
}

// The rigid geared model that knows the reducer's compliance c and may take a hysteresis on every joint.
MotionModel hysteresis_model(double c) {
  MotionModel m = rigid_geared();
  m.hysteresis_compliance_rad_per_Nm = c;
  return m;
}

TEST(ReadingModelSelection, RecoversTheReducersHysteresisAlongAPath) {
  const double c = 1e-4;
  const Eigen::Vector3d eta(0.0, 1.2e-4, 0.6e-4);  // half losses: 0.8 and 0.4 arcmin of loss
  const DriveData d = hysteresis_data(3000, 21, eta, c);
  LmOptions o;
  o.encoder_sigma = kSigma;
  MotionModel candidates;
  candidates.hysteresis = {true, true, true};
  const DriveEffectSelection s = select_drive_effects(d.problem, d.omega, d.tau, o, hysteresis_model(c), {}, candidates);
  EXPECT_FALSE(s.model.hysteresis[0]);
  EXPECT_TRUE(s.model.hysteresis[1]);
  EXPECT_TRUE(s.model.hysteresis[2]);
  ASSERT_FALSE(s.dropped.empty());
  EXPECT_NE(s.dropped.front().find("hysteresis of joint 1 (its mesh torque spans less"), std::string::npos)
      << s.dropped.front();
  for (std::size_t i : {1u, 2u}) {
    const double truth = eta[static_cast<Eigen::Index>(i)];
    EXPECT_LT(std::abs(s.fit.hysteresis[i] - truth), std::max(4.0 * s.fit.hysteresis_sigma[i], 0.02 * truth)) << i;
  }
  EXPECT_LT(worst_in_sigmas(d, s.fit.result), 4.0);
  // Without it the same readings calibrate far from the truth.
  const MotionFit blind = calibrate_in_motion(d.problem, d.omega, d.tau, o, hysteresis_model(c));
  EXPECT_GT(worst_in_sigmas(d, blind.result), 20.0);
}

TEST(ReadingModelSelection, KeepsNoHysteresisOnARobotWithout) {
  const double c = 1e-4;
  const DriveData d = hysteresis_data(3000, 23, Eigen::Vector3d::Zero(), c);
  LmOptions o;
  o.encoder_sigma = kSigma;
  MotionModel candidates;
  candidates.hysteresis = {true, true, true};
  const DriveEffectSelection s = select_drive_effects(d.problem, d.omega, d.tau, o, hysteresis_model(c), {}, candidates);
  EXPECT_EQ(s.model.hysteresis, (std::array<bool, 3>{false, false, false}));
  EXPECT_TRUE(s.kept.empty());
  EXPECT_EQ(s.dropped.size(), 3u);
  EXPECT_LT(worst_in_sigmas(d, s.fit.result), 4.0);
}

}  // namespace
}  // namespace gpm::calib
