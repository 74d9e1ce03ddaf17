// Tests of calib/motion_correction.cpp: readings generated with a known
// transmission compliance and latch skew are calibrated back to the true
// geometry and nuisance values within their reported 1-sigma, while the rigid
// calibration of the same readings is biased far beyond its own 1-sigma; the
// reading correction is the exact inverse of the generating model; the twist
// of the motor-side friction is recovered the same way (and ignoring it
// biases the fit); a joint at constant torque leaves its compliance to dth;
// readings of passive links that sit at the end of their axial play by the
// sign of their force give back the play, and ignoring it biases the fit;
// a twist that responds to the torque of the sample before is recovered
// (and ignoring it biases the fit); the cyclic encoder error carried in the
// covariance adds what finite-difference responses of the fit to it say; the
// reading sensitivities of the nuisance Jacobian (the dth columns of the ML
// Jacobian) equal central differences over the readings; the hysteresis
// state follows the torque at half its rate until it slides at +-1, and holds
// through a reversal smaller than its threshold; the score test of an
// effect left out agrees with the chi-square the full fit takes out; a
// friction that leads the speed is named as the drives' friction dynamics;
// samples whose rotors rest weigh less, and so pass the model test.
#include "calib/motion_correction.hpp"

#include <cmath>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "calib/crb.hpp"
#include "calib/identifiability.hpp"
#include "calib/model_test.hpp"
#include "calib/residuals.hpp"
#include "calib/paper_values.hpp"
#include "calib/synthetic.hpp"
#include "models/errors.hpp"
#include "models/kinematics.hpp"
#include "models/rng.hpp"

namespace gpm::calib {
namespace {

constexpr double kSigma = 1e-5;
const std::array<double, 5> kNu = {50e-6, 100e-6, 1.0e-4, 1.2e-4, 0.8e-4};

struct MotionData {
  Problem problem;
  std::vector<Eigen::Vector3d> omega, tau;
  Geometry truth;
};

// n samples of the Table-5 robot with speeds and torques drawn at random; the
// readings follow theta_m = theta_a - dth - s omega + c tau (the model inverted).
MotionData make_data(int n, std::uint64_t seed) {
  Robot a;
  a.geometry = table5_actual();
  const Samples smp = samples_at(a, disc_poses(a, n, a.home, 100.0, seed), kSigma, seed + 1);
  MotionData d;
  d.truth = a.geometry;
  Rng rng(seed + 2);
  for (std::size_t j = 0; j < smp.size(); ++j) {
    const Eigen::Vector3d w(rng.normal(0, 1.0), rng.normal(0, 1.0), rng.normal(0, 1.0));
    const Eigen::Vector3d t(rng.normal(0, 3.0), rng.normal(0, 3.0), rng.normal(0, 3.0));
    const Eigen::Vector3d s(0.0, kNu[0], kNu[1]), c(kNu[2], kNu[3], kNu[4]);
    d.omega.push_back(w);
    d.tau.push_back(t);
    d.problem.theta_m.push_back(smp.theta_m[j] - s.cwiseProduct(w) + c.cwiseProduct(t));
  }
  d.problem.start = Robot{}.geometry;
  for (int k : {kXa1, kYa1, kXa2, kYa2}) d.problem.start.values[k] = a.geometry.values[k];
  d.problem.free = default_free_mask();
  return d;
}

// LM options with the readings' 1-sigma kSigma.
LmOptions at_sigma() {
  LmOptions o;
  o.encoder_sigma = kSigma;
  return o;
}

// The largest error of the free parameters of fit r against d's truth, in r's 1-sigma.
double worst_in_sigmas(const MotionData& d, const Result& r) {
  double w = 0.0;
  for (int k = 0; k < kNumParams; ++k)
    if (d.problem.free[k]) w = std::max(w, std::abs(r.geometry.values[k] - d.truth.values[k]) / r.sigma[k]);
  return w;
}

// The twist's lag h, the skew and compliance kNu and the geometry of fit
// within 4 of their sigmas of d's truth.
void expect_lag_recovered(const MotionData& d, const MotionFit& fit, const Eigen::Vector3d& h) {
  for (std::size_t k = 0; k < 3; ++k) {
    ASSERT_TRUE(std::isfinite(fit.torque_before_sigma[k]));
    EXPECT_LT(std::abs(fit.torque_before[k] - h[static_cast<Eigen::Index>(k)]), 4.0 * fit.torque_before_sigma[k])
        << "h of joint " << k + 1;
  }
  for (int k = 0; k < 5; ++k) EXPECT_LT(std::abs(fit.nu[k] - kNu[k]), 4.0 * fit.nu_sigma[k]) << "nuisance " << k;
  EXPECT_LT(worst_in_sigmas(d, fit.result), 4.0);
}

TEST(MotionCorrection, CorrectionInvertsTheGeneratingModel) {
  const std::vector<Eigen::Vector3d> th{{1.0, 2.0, 3.0}}, w{{0.5, -1.0, 2.0}}, t{{3.0, -2.0, 1.0}};
  const auto out = correct_readings(th, w, t, kNu);
  EXPECT_NEAR(out[0][0], 1.0 - kNu[2] * 3.0, 1e-15);
  EXPECT_NEAR(out[0][1], 2.0 + kNu[0] * -1.0 - kNu[3] * -2.0, 1e-15);
  EXPECT_NEAR(out[0][2], 3.0 + kNu[1] * 2.0 - kNu[4] * 1.0, 1e-15);
}

TEST(MotionCorrection, RecoversGeometryComplianceAndSkewWithinTheirSigma) {
  const MotionData d = make_data(600, 11);
  const LmOptions o = at_sigma();
  const MotionFit fit = calibrate_in_motion(d.problem, d.omega, d.tau, o);
  for (int k = 0; k < 5; ++k) {
    ASSERT_TRUE(std::isfinite(fit.nu_sigma[k]));
    EXPECT_LT(std::abs(fit.nu[k] - kNu[k]), 4.0 * fit.nu_sigma[k]) << "nuisance " << k;
    EXPECT_LT(fit.nu_sigma[k], 0.05 * kNu[k]) << "nuisance " << k << " poorly determined";
  }
  for (int k = 0; k < kNumParams; ++k) {
    if (!d.problem.free[k]) continue;
    EXPECT_LT(std::abs(fit.result.geometry.values[k] - d.truth.values[k]), 4.0 * fit.result.sigma[k])
        << param_name(k);
  }
  // The rigid fit of the same readings is biased far beyond its own 1-sigma.
  const Result rigid = calibrate_lm(d.problem, o);
  EXPECT_GT(worst_in_sigmas(d, rigid), 10.0);
}

// Readings with compliance and skew fitted without the compliance: the
// score test names the compliance first, its chi-square drop (one
// linearisation at the reduced fit) within 5 % of the drop the full fit
// makes (the likelihood ratio, two fits); the full fit leaves nothing to name.
TEST(MotionCorrection, LeftOutEffectsNamesTheComplianceLeftOutAsTheFullFitMeasuresIt) {
  const MotionData d = make_data(600, 11);
  const LmOptions o = at_sigma();
  MotionModel stiff;
  stiff.compliance = stiff.friction = false;
  const MotionFit reduced = calibrate_in_motion(d.problem, d.omega, d.tau, o, stiff);
  const MotionFit full = calibrate_in_motion(d.problem, d.omega, d.tau, o);
  const std::vector<LeftOutEffect> named = left_out_effects(d.problem, d.omega, d.tau, stiff, reduced, kSigma);
  ASSERT_FALSE(named.empty());
  EXPECT_EQ(named.front().name, "transmission compliance");
  EXPECT_EQ(named.front().columns, 3);
  const double lr = model_test(reduced.result.geometry, d.problem.free, reduced.corrected, kSigma).chi2 -
                    model_test(full.result.geometry, d.problem.free, full.corrected, kSigma).chi2;
  EXPECT_NEAR(named.front().chi2_drop, lr, 0.05 * lr);
  const std::vector<LeftOutEffect> none = left_out_effects(d.problem, d.omega, d.tau, MotionModel{}, full, kSigma);
  for (const LeftOutEffect& e : none) ADD_FAILURE() << e.name << " named: chi2 down by " << e.chi2_drop;
}

// Readings with an error once per motor revolution on joint 2 (10:1, 20
// sigma): named when the encoders read the motors; where they turn with the
// joints (after the reducer) no reducer effect is a candidate to name.
TEST(MotionCorrection, LeftOutEffectsNameTheReducersOnlyBehindAMotorEncoder) {
  MotionData d = make_data(600, 13);
  for (Eigen::Vector3d& theta_m : d.problem.theta_m) theta_m[1] += 20.0 * kSigma * std::sin(10.0 * theta_m[1]);
  const LmOptions o = at_sigma();
  MotionModel motor;
  motor.gear_ratio = 10.0;
  const MotionFit fit = calibrate_in_motion(d.problem, d.omega, d.tau, o, motor);
  const std::vector<LeftOutEffect> named = left_out_effects(d.problem, d.omega, d.tau, motor, fit, kSigma);
  ASSERT_FALSE(named.empty());
  EXPECT_EQ(named.front().name, "an error once per motor revolution of joint 2");
  MotionModel joint = motor;
  joint.encoder_on_motor = false;
  for (const LeftOutEffect& e : left_out_effects(d.problem, d.omega, d.tau, joint, fit, kSigma))
    EXPECT_TRUE(e.name.find("motor revolution") == std::string::npos && e.name.find("backlash") == std::string::npos)
        << e.name << " named behind an encoder that turns with the joint";
}

// Readings whose friction twist acts on the speed 10 ms ahead, c_i F_i
// tanh((omega_i + 0.01 s alpha_i) / v) at v = 0.5 rad/s, fitted with the
// twist of the speed alone: the drives' friction dynamics are named first;
// with the twist of the speed itself nothing is named, and without the
// accelerations the candidate cannot be scored.
TEST(MotionCorrection, LeftOutEffectsNameAFrictionThatLeadsTheSpeed) {
  const std::array<double, 3> cf = {2e-4, -3e-4, 2.5e-4};
  MotionModel model;
  model.load.friction_speed_rad_s = 0.5;
  const LmOptions o = at_sigma();
  const auto named_with_lead = [&](double lead_s, bool with_alpha) {
    MotionData d = make_data(600, 17);
    Rng rng(99);
    std::vector<Eigen::Vector3d> alpha;
    for (std::size_t j = 0; j < d.omega.size(); ++j) {
      alpha.emplace_back(rng.normal(0, 20.0), rng.normal(0, 20.0), rng.normal(0, 20.0));
      for (int k = 0; k < 3; ++k)
        d.problem.theta_m[j][k] -=
            cf[static_cast<std::size_t>(k)] * std::tanh((d.omega[j][k] + lead_s * alpha[j][k]) / 0.5);
    }
    const MotionFit fit = calibrate_in_motion(d.problem, d.omega, d.tau, o, model, alpha);
    return left_out_effects(d.problem, d.omega, d.tau, model, fit, kSigma,
                            with_alpha ? alpha : std::vector<Eigen::Vector3d>{});
  };
  const std::vector<LeftOutEffect> lead = named_with_lead(0.01, true);
  ASSERT_FALSE(lead.empty());
  EXPECT_NE(lead.front().name.find("friction dynamics"), std::string::npos) << lead.front().name;
  EXPECT_EQ(lead.front().columns, 3);
  for (const LeftOutEffect& e : named_with_lead(0.0, true)) ADD_FAILURE() << e.name << " named without a lead";
  for (const LeftOutEffect& e : named_with_lead(0.01, false))
    EXPECT_EQ(e.name.find("friction dynamics"), std::string::npos) << "named without accelerations";
}

TEST(MotionCorrection, WithoutNuisanceItIsTheRigidCalibration) {
  const MotionData d = make_data(100, 3);
  const LmOptions o = at_sigma();
  MotionModel none;
  none.skew = none.compliance = false;
  const MotionFit fit = calibrate_in_motion(d.problem, d.omega, d.tau, o, none);
  const Result rigid = calibrate_lm(d.problem, o);
  for (int k = 0; k < kNumParams; ++k) EXPECT_NEAR(fit.result.geometry.values[k], rigid.geometry.values[k], 1e-9);
  for (double v : fit.nu) EXPECT_EQ(v, 0.0);
}

TEST(MotionCorrection, ATorqueOffJointsComplianceIsNotEstimated) {
  MotionData d = make_data(300, 7);
  // Joint 1 torque-off: no transmitted torque, so its compliance is unobservable.
  for (std::size_t j = 0; j < d.tau.size(); ++j) {
    d.problem.theta_m[j][0] -= kNu[2] * d.tau[j][0];
    d.tau[j][0] = 0.0;
  }
  const LmOptions o = at_sigma();
  const MotionFit fit = calibrate_in_motion(d.problem, d.omega, d.tau, o);
  EXPECT_EQ(fit.nu[2], 0.0);
  EXPECT_TRUE(std::isnan(fit.nu_sigma[2]));
  for (int k : {0, 1, 3, 4}) EXPECT_LT(std::abs(fit.nu[k] - kNu[k]), 4.0 * fit.nu_sigma[k]) << "nuisance " << k;
}

// Readings with the friction twist c_i F_i tanh(omega_i / 0.01 rad/s) added
// to the link angle (theta_m lower by it): the default model recovers c_i F_i
// within 4 sigma and the geometry within 4 sigma; without the friction term
// the same fit is biased beyond 4 of its sigmas.
TEST(MotionCorrection, RecoversTheFrictionTwistAndIgnoringItBiasesTheFit) {
  MotionData d = make_data(600, 13);
  const std::array<double, 3> cf = {2e-5, -3e-5, 4e-5};
  for (std::size_t j = 0; j < d.omega.size(); ++j)
    for (int k = 0; k < 3; ++k) d.problem.theta_m[j][k] -= cf[static_cast<std::size_t>(k)] * std::tanh(d.omega[j][k] / 0.01);
  const LmOptions o = at_sigma();
  const MotionFit fit = calibrate_in_motion(d.problem, d.omega, d.tau, o);
  for (std::size_t k = 0; k < 3; ++k) {
    ASSERT_TRUE(std::isfinite(fit.friction_sigma[k]));
    EXPECT_LT(std::abs(fit.friction[k] - cf[k]), 4.0 * fit.friction_sigma[k]) << "c F of joint " << k + 1;
  }
  for (int k = 0; k < 5; ++k) EXPECT_LT(std::abs(fit.nu[k] - kNu[k]), 4.0 * fit.nu_sigma[k]) << "nuisance " << k;
  EXPECT_LT(worst_in_sigmas(d, fit.result), 4.0);
  MotionModel no_friction;
  no_friction.friction = false;
  no_friction.sandwich = false;  // judged by the noise model's 1-sigma (the sandwich widens it to the misfit)
  const MotionFit biased = calibrate_in_motion(d.problem, d.omega, d.tau, o, no_friction);
  EXPECT_EQ(biased.friction[0], 0.0);
  EXPECT_TRUE(std::isnan(biased.friction_sigma[0]));
  EXPECT_GT(worst_in_sigmas(d, biased.result), 4.0);
}

// Every fourth sample at rest (its rates read 0), its twist anywhere within
// +-spread c F (uniform); the others slide, their twist c F tanh(omega / 0.01).
MotionData data_with_rests(double spread) {
  MotionData d = make_data(800, 17);
  const std::array<double, 3> cf = {4e-5, -5e-5, 6e-5};
  Rng rng(18);
  for (std::size_t j = 0; j < d.omega.size(); ++j)
    for (int k = 0; k < 3; ++k) {
      const double c = cf[static_cast<std::size_t>(k)];
      if (j % 4 == 0) {  // at rest: no skew's share either
        d.problem.theta_m[j][k] += (k == 0 ? 0.0 : kNu[static_cast<std::size_t>(k) - 1]) * d.omega[j][k];
        d.omega[j][k] = 0.0;
      }
      const double twist = j % 4 == 0 ? spread * rng.uniform(-1.0, 1.0) * c : c * std::tanh(d.omega[j][k] / 0.01);
      d.problem.theta_m[j][k] -= twist;  // theta_m = theta_a - dth - s omega + c tau - twist
    }
  return d;
}

// Weighted by calib/sample_weights.hpp, the rest's twist is the variance the
// fit's chi-square expects. The model test judges the residuals unweighted:
// by the encoders' noise alone it fails, the rest's twist exceeds it; with
// what the doubt the model states (the data sheet's compliance times the
// drives' friction, here the twist's own) adds on average expected
// (MotionFit::doubt) it passes. The misfit's sandwich is computed (the
// residuals exceed the noise alone) but not taken: these rests' twists are
// independent from sample to sample, so it is no wider.
TEST(MotionCorrection, SamplesWhoseRotorsRestWeighLessAndTheTestExpectsTheirDoubt) {
  MotionData d = data_with_rests(1.0);
  const std::array<double, 3> cf = {4e-5, -5e-5, 6e-5};  // data_with_rests's c F
  const LmOptions o = at_sigma();
  MotionModel weighted;
  weighted.stick_speed_rad_s = 0.05;
  weighted.load.coulomb_Nm = {0.4, 0.5, 0.6};  // with the stated compliance 1e-4: c F of data_with_rests
  const MotionFit plain = calibrate_in_motion(d.problem, d.omega, d.tau, o);
  const MotionFit fit = calibrate_in_motion(d.problem, d.omega, d.tau, o, weighted);
  ASSERT_TRUE(plain.weight.empty());
  ASSERT_EQ(fit.weight.size(), fit.kept.size());
  for (std::size_t j = 0; j < fit.weight.size(); ++j) {
    if (j % 4 == 0) {
      EXPECT_LT(fit.weight[j], 0.7) << j;
    } else if (d.omega[j].cwiseAbs().minCoeff() > 0.2) {  // 4 stick speeds
      EXPECT_GT(fit.weight[j], 0.99) << j;
    }
  }
  // The weighted chi-square is the noise's (chi2/dof within 3 of its
  // 1-sigma sqrt(2 / dof)); the unweighted one is not.
  EXPECT_LT(fit.chi2_per_dof, 1.0 + 3.0 * std::sqrt(2.0 / 800.0)) << fit.chi2_per_dof;
  EXPECT_GT(plain.chi2_per_dof, 1.0 + 3.0 * std::sqrt(2.0 / 800.0)) << plain.chi2_per_dof;
  const ModelTest t_plain = model_test(plain.result.geometry, d.problem.free, plain.corrected, kSigma);
  const ModelTest t_noise = model_test(fit.result.geometry, d.problem.free, fit.corrected, kSigma);
  const ModelTest t_fit = model_test(fit.result.geometry, d.problem.free, fit.corrected, kSigma, 0.01, 0.0, fit.doubt);
  EXPECT_FALSE(t_plain.passed) << t_plain.rms_ratio;
  EXPECT_FALSE(t_noise.passed) << t_noise.rms_ratio;
  EXPECT_EQ(plain.doubt.mean, 0.0);
  EXPECT_GT(fit.doubt.mean, 0.0);
  EXPECT_EQ(t_fit.chi2, t_noise.chi2);
  EXPECT_TRUE(t_fit.passed) << t_fit.p_value;
  EXPECT_FALSE(fit.sandwich_used);
  for (std::size_t k = 0; k < 3; ++k)
    EXPECT_LT(std::abs(fit.friction[k] - cf[k]), 4.0 * fit.friction_sigma[k]) << "c F of joint " << k + 1;
  EXPECT_LT(worst_in_sigmas(d, fit.result), 4.0);
}

// Rests held over runs of 40 consecutive samples, each run's twist one value
// within +-c F: the doubt explains the residuals' size and the model test
// passes, but the twist moves the estimate as one value per run, which the
// weights, independent per sample, do not state: the sandwich, from the
// residuals' autocorrelation, is wider and taken.
TEST(MotionCorrection, RestsHeldOverManySamplesWidenTheOneSigma) {
  MotionData d = make_data(800, 17);
  const std::array<double, 3> cf = {4e-5, -5e-5, 6e-5};
  Rng rng(18);
  std::array<double, 3> held{};
  for (std::size_t j = 0; j < d.omega.size(); ++j)
    for (int k = 0; k < 3; ++k) {
      const auto kk = static_cast<std::size_t>(k);
      const bool rest = (j / 40) % 4 == 0;
      if (rest && j % 40 == 0) held[kk] = rng.uniform(-1.0, 1.0) * cf[kk];
      if (rest) {  // at rest: no skew's share either
        d.problem.theta_m[j][k] += (k == 0 ? 0.0 : kNu[kk - 1]) * d.omega[j][k];
        d.omega[j][k] = 0.0;
      }
      d.problem.theta_m[j][k] -= rest ? held[kk] : cf[kk] * std::tanh(d.omega[j][k] / 0.01);
    }
  MotionModel weighted;
  weighted.stick_speed_rad_s = 0.05;
  weighted.load.coulomb_Nm = {0.4, 0.5, 0.6};  // with the stated compliance 1e-4: the twists' c F
  const MotionFit fit = calibrate_in_motion(d.problem, d.omega, d.tau, at_sigma(), weighted);
  const ModelTest t = model_test(fit.result.geometry, d.problem.free, fit.corrected, kSigma, 0.01, 0.0, fit.doubt);
  EXPECT_TRUE(t.passed) << t.p_value;
  EXPECT_TRUE(fit.sandwich_used);
  EXPECT_GT(fit.sandwich_inflation, 1.0);
}

// A rest whose twist lies three times beyond +-c F: misfit where a joint is
// slow. The model states the doubt of +-c F only, so the test, expecting
// that doubt and no more, fails, and the misfit's sandwich widens the 1-sigma.
TEST(MotionCorrection, ARestBeyondItsDoubtStillFailsTheTest) {
  MotionData d = data_with_rests(3.0);
  MotionModel weighted;
  weighted.stick_speed_rad_s = 0.05;
  weighted.load.coulomb_Nm = {0.4, 0.5, 0.6};  // with the stated compliance 1e-4: c F of data_with_rests
  const MotionFit fit = calibrate_in_motion(d.problem, d.omega, d.tau, at_sigma(), weighted);
  ASSERT_GT(fit.doubt.mean, 0.0);
  const ModelTest t = model_test(fit.result.geometry, d.problem.free, fit.corrected, kSigma, 0.01, 0.0, fit.doubt);
  EXPECT_FALSE(t.passed) << t.chi2 << " for " << t.dof << " + " << t.doubt_chi2;
  EXPECT_TRUE(fit.sandwich_used);
}

TEST(MotionCorrection, AConstantTorqueJointsTwistGoesIntoItsOffset) {
  MotionData d = make_data(300, 7);
  // Joint 1 held at a constant 2 N m: it twists by the constant c1 x 2.
  const double tau0 = 2.0;
  for (std::size_t j = 0; j < d.tau.size(); ++j) {
    d.problem.theta_m[j][0] += kNu[2] * (tau0 - d.tau[j][0]);
    d.tau[j][0] = tau0;
  }
  const LmOptions o = at_sigma();
  const MotionFit fit = calibrate_in_motion(d.problem, d.omega, d.tau, o);
  EXPECT_EQ(fit.nu[2], 0.0);
  EXPECT_TRUE(std::isnan(fit.nu_sigma[2]));
  // theta_a = theta_m + dth - c tau0: the offset absorbs -c1 tau0.
  EXPECT_LT(std::abs(fit.result.geometry[kDth1] - (d.truth[kDth1] - kNu[2] * tau0)), 4.0 * fit.result.sigma[kDth1]);
  for (int k : {0, 1, 3, 4}) EXPECT_LT(std::abs(fit.nu[k] - kNu[k]), 4.0 * fit.nu_sigma[k]) << "nuisance " << k;
}

// Joint clearance: each passive link is lb_i + d_i in tension and lb_i - d_i
// in compression, the sign of its force T_i = tau_i / (d|C - B_i| / dtheta_i)
// by virtual work (finite differences, independent of the calibration's
// formula); readings by IK of that sample's geometry, with the compliance
// and skew of make_data. The clearance model recovers d_i and the geometry
// within 4 sigma and leaves out the samples with some |T_i| below
// tension_min_N (judged at the start geometry: to 10 %); without it the same
// samples give a fit biased beyond 4 sigma; with a force's 1-sigma the
// samples whose signs are near the threshold weigh less.
TEST(MotionCorrection, RecoversTheJointClearanceAndIgnoringItBiasesTheFit) {
  const std::array<double, 3> play = {0.010, 0.008, 0.012};  // mm
  Robot a;
  a.geometry = table5_actual();
  const std::vector<Eigen::Vector2d> poses = disc_poses(a, 800, a.home, 100.0, 21);
  MotionData d;
  d.truth = a.geometry;
  d.problem.start = Robot{}.geometry;
  for (int k : {kXa1, kYa1, kXa2, kYa2}) d.problem.start.values[k] = a.geometry.values[k];
  d.problem.free = default_free_mask();
  Rng rng(22);
  MotionModel model;  // no load: the drive torque is the transmitted torque
  std::vector<double> weakest;  // per sample, min |T_i| (N)
  for (std::size_t j = 0; j < poses.size(); ++j) {
    const Eigen::Vector3d w(rng.normal(0, 1.0), rng.normal(0, 1.0), rng.normal(0, 1.0));
    const Eigen::Vector3d t(rng.normal(0, 3.0), rng.normal(0, 3.0), rng.normal(0, 3.0));
    const JointAngles q = inverse_kinematics(a.geometry, poses[j]);
    Geometry gj = a.geometry;
    double weak = INFINITY;
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector2d A(a.geometry[xa(i)], a.geometry[ya(i)]);
      const auto dist = [&](double th) {
        return (poses[j] - A - a.geometry.la_(i) * Eigen::Vector2d(std::cos(th), std::sin(th))).norm();
      };
      const double tension = t[i] / (1e-3 * (dist(q.theta_a[i] + 1e-6) - dist(q.theta_a[i] - 1e-6)) / 2e-6);
      gj.values[lb(i)] += (tension > 0.0 ? 1.0 : -1.0) * play[static_cast<std::size_t>(i)];
      weak = std::min(weak, std::abs(tension));
    }
    weakest.push_back(weak);
    const JointAngles qj = inverse_kinematics(gj, poses[j]);
    const Eigen::Vector3d s(0.0, kNu[0], kNu[1]), c(kNu[2], kNu[3], kNu[4]);
    const Eigen::Vector3d noise(rng.normal(0, kSigma), rng.normal(0, kSigma), rng.normal(0, kSigma));
    d.omega.push_back(w);
    d.tau.push_back(t);
    d.problem.theta_m.push_back(readings_from_active(gj, qj.theta_a) + noise - s.cwiseProduct(w) + c.cwiseProduct(t));
  }
  const LmOptions o = at_sigma();
  model.clearance = true;
  const MotionFit fit = calibrate_in_motion(d.problem, d.omega, d.tau, o, model);
  ASSERT_LT(fit.kept.size(), poses.size());
  ASSERT_GT(fit.kept.size(), poses.size() / 2);
  std::vector<bool> kept(poses.size(), false);
  for (std::size_t j : fit.kept) kept[j] = true;
  for (std::size_t j = 0; j < poses.size(); ++j) {
    if (weakest[j] > 1.1 * model.tension_min_N) {
      EXPECT_TRUE(kept[j]) << "sample " << j << " min |T| " << weakest[j];
    }
    if (weakest[j] < 0.9 * model.tension_min_N) {
      EXPECT_FALSE(kept[j]) << "sample " << j << " min |T| " << weakest[j];
    }
  }
  for (std::size_t k = 0; k < 3; ++k) {
    ASSERT_TRUE(std::isfinite(fit.clearance_sigma[k]));
    EXPECT_LT(std::abs(fit.clearance[k] - play[k]), 4.0 * fit.clearance_sigma[k]) << "play of chain " << k + 1;
    EXPECT_LT(fit.clearance_sigma[k], 0.2 * play[k]) << "play of chain " << k + 1 << " poorly determined";
  }
  for (int k = 0; k < 5; ++k) EXPECT_LT(std::abs(fit.nu[k] - kNu[k]), 4.0 * fit.nu_sigma[k]) << "nuisance " << k;
  EXPECT_LT(worst_in_sigmas(d, fit.result), 4.0);
  EXPECT_TRUE(clearance_detected(fit));
  // A link's force known within 1 N: the samples whose weakest force is near
  // the threshold weigh less (a sign wrong with Phi(-|T|)), those far from
  // it 1; the play is still recovered.
  MotionModel doubted = model;
  doubted.tension_sigma_N = 1.0;
  const MotionFit weighed = calibrate_in_motion(d.problem, d.omega, d.tau, o, doubted);
  ASSERT_EQ(weighed.weight.size(), weighed.kept.size());
  int near = 0, near_less = 0;  // (a sign the fit's own forces put below the threshold is not used: no doubt)
  for (std::size_t k = 0; k < weighed.kept.size(); ++k) {
    const double weak = weakest[weighed.kept[k]];
    if (weak > 6.0) {
      EXPECT_GT(weighed.weight[k], 0.999) << "sample " << weighed.kept[k];
    }
    if (weak < 1.8) ++near, near_less += weighed.weight[k] < 0.99;
  }
  EXPECT_GT(near, 10);
  EXPECT_GE(near_less, 0.9 * near);
  for (std::size_t k = 0; k < 3; ++k)
    EXPECT_LT(std::abs(weighed.clearance[k] - play[k]), 4.0 * weighed.clearance_sigma[k]) << "play of chain " << k + 1;
  model.clearance = false;
  model.sandwich = false;  // judged by the noise model's 1-sigma (the sandwich widens it to the misfit)
  const MotionFit biased = calibrate_in_motion(d.problem, d.omega, d.tau, o, model);
  EXPECT_EQ(biased.kept.size(), poses.size());
  EXPECT_GT(worst_in_sigmas(d, biased.result), 4.0);
}

// A threshold no sample clears is lowered to keep min_kept_share of them
// (the strongest: every kept sample's forces clear the threshold used).
TEST(MotionCorrection, TooHighAForceThresholdKeepsTheStrongestShare) {
  const MotionData d = make_data(200, 23);
  const LmOptions o = at_sigma();
  MotionModel model;
  model.clearance = true;
  model.tension_min_N = 1e4;
  model.min_kept_share = 0.3;
  const MotionFit fit = calibrate_in_motion(d.problem, d.omega, d.tau, o, model);
  EXPECT_EQ(fit.kept.size(), 60u);
  EXPECT_LT(fit.tension_min_N, 1e4);
  EXPECT_GT(fit.tension_min_N, 0.0);
  model.min_kept_share = 0.0;  // no floor: nothing is left, which calibrate_lm refuses
  EXPECT_THROW(calibrate_in_motion(d.problem, d.omega, d.tau, o, model), InputError);
}

// Chain 1 held at one torque sign: its link stays at one end of the play, a
// constant length change that lb1 absorbs; the play is not estimated.
TEST(MotionCorrection, AOneSignedLinksPlayIsNotEstimated) {
  MotionData d = make_data(300, 9);
  for (std::size_t j = 0; j < d.tau.size(); ++j) {
    d.problem.theta_m[j][0] += kNu[2] * (2.0 - d.tau[j][0]);
    d.tau[j][0] = 2.0;
  }
  const LmOptions o = at_sigma();
  MotionModel model;
  model.clearance = true;
  model.tension_min_N = 0.0;
  const MotionFit fit = calibrate_in_motion(d.problem, d.omega, d.tau, o, model);
  EXPECT_EQ(fit.clearance[0], 0.0);
  EXPECT_TRUE(std::isnan(fit.clearance_sigma[0]));
  EXPECT_TRUE(std::isfinite(fit.clearance_sigma[1]));
}

// Without a play in the data the estimated d_i stay within 3 sigma of 0 (no
// clearance detected); the test by hand: |d_i| >= k sigma_i for some
// estimated chain, a play not estimated (sigma NaN) never counts.
TEST(MotionCorrection, NoClearanceIsDetectedWhereThereIsNone) {
  const MotionData d = make_data(300, 31);
  const LmOptions o = at_sigma();
  MotionModel model;
  model.clearance = true;
  model.tension_min_N = 0.0;
  const MotionFit fit = calibrate_in_motion(d.problem, d.omega, d.tau, o, model);
  for (std::size_t k = 0; k < 3; ++k) ASSERT_TRUE(std::isfinite(fit.clearance_sigma[k])) << "chain " << k + 1;
  EXPECT_FALSE(clearance_detected(fit));
  MotionFit hand;
  hand.clearance = {0.0, 0.0029, 0.0};
  hand.noise_sigma.clearance = {NAN, 0.001, 0.001};  // the test weighs by the noise model's 1-sigma
  hand.clearance_sigma = {NAN, 1.0, 1.0};             // not by the stated one
  EXPECT_FALSE(clearance_detected(hand));
  EXPECT_TRUE(clearance_detected(hand, 2.8));
  hand.clearance = {1.0, -0.0031, 0.0};
  EXPECT_TRUE(clearance_detected(hand));  // chain 2, negative d: two-sided
  hand.clearance[1] = 0.0;
  EXPECT_FALSE(clearance_detected(hand));  // chain 1's play is not estimated
}

// The joint bound: without nuisance values it is the geometry-only bound of
// calib/crb.hpp (two algorithms); each nuisance value estimated can only
// widen it; and it agrees with the 1-sigma the fit reports from its own
// joint Jacobian at the estimate (to 5 %).
TEST(MotionCorrection, JointBoundCrossChecks) {
  const MotionData d = make_data(400, 17);
  Robot a;
  a.geometry = d.truth;
  const Samples smp = samples_at(a, disc_poses(a, 400, a.home, 100.0, 17), 0.0, 18);
  MotionModel none;
  none.skew = none.compliance = false;
  const auto plain = crb_sigma(d.truth, d.problem.free, smp.theta_m, kSigma);
  const auto rigid = motion_crb(d.truth, d.problem.free, smp.theta_m, d.omega, d.tau, none, {}, kSigma);
  const auto joint = motion_crb(d.truth, d.problem.free, smp.theta_m, d.omega, d.tau, MotionModel{}, {}, kSigma);
  const LmOptions o = at_sigma();
  const MotionFit fit = calibrate_in_motion(d.problem, d.omega, d.tau, o);
  for (int k = 0; k < kNumParams; ++k) {
    if (!d.problem.free[k]) {
      EXPECT_TRUE(std::isnan(joint[static_cast<std::size_t>(k)]));
      continue;
    }
    const auto K = static_cast<std::size_t>(k);
    EXPECT_NEAR(rigid[K], plain[K], 1e-9 * plain[K]) << param_name(k);
    EXPECT_GE(joint[K], plain[K] * (1.0 - 1e-9)) << param_name(k);
    EXPECT_NEAR(fit.result.sigma[K], joint[K], 0.05 * joint[K]) << param_name(k);
  }
  EXPECT_THROW(motion_crb(d.truth, d.problem.free, smp.theta_m, d.omega, {}, none, {}, kSigma), InputError);
}

// Consecutive samples whose twist is c_i tau_i(j) + h_i (tau_i(j-1) - tau_i(j)):
// with MotionModel::torque_before h_i, the static compliance c_i and the
// geometry come back within 4 sigma; the model without it is biased beyond 4
// of its sigmas.
TEST(MotionCorrection, RecoversTheTwistOfTheTorqueBefore) {
  MotionData d = make_data(600, 19);
  const Eigen::Vector3d h(-0.5e-4, 0.6e-4, -0.4e-4);
  for (std::size_t j = 1; j < d.tau.size(); ++j) d.problem.theta_m[j] += h.cwiseProduct(d.tau[j - 1] - d.tau[j]);
  const LmOptions o = at_sigma();
  MotionModel before;
  before.torque_before = true;
  const MotionFit fit = calibrate_in_motion(d.problem, d.omega, d.tau, o, before);
  expect_lag_recovered(d, fit, h);
  MotionModel plain;
  plain.sandwich = false;  // judged by the noise model's 1-sigma (the sandwich widens it to the misfit)
  const MotionFit biased = calibrate_in_motion(d.problem, d.omega, d.tau, o, plain);
  EXPECT_EQ(biased.torque_before[0], 0.0);
  EXPECT_TRUE(std::isnan(biased.torque_before_sigma[0]));
  EXPECT_GT(worst_in_sigmas(d, biased.result), 4.0);
}

// With the drives' record of the torques between samples
// (MotionModel::torque_between, here the torque of the sample before and an
// independent swing of the periods between), a twist c_i tau_i(j) +
// h_i (between_i(j) - tau_i(j)) comes back within 4 sigma (h, c and the
// geometry); the lag on the sample before's torque instead misses the
// swing: its residuals are far above the noise. A record of the wrong
// length is refused.
TEST(MotionCorrection, RecoversTheTwistOfTheTorquesBetweenSamples) {
  MotionData d = make_data(600, 23);
  const Eigen::Vector3d h(0.6e-4, -0.5e-4, 0.7e-4);
  std::vector<Eigen::Vector3d> between(d.tau.size());
  for (std::size_t j = 0; j < d.tau.size(); ++j) {
    const double t = static_cast<double>(j);
    between[j] = d.tau[j > 0 ? j - 1 : 0] + 0.8 * Eigen::Vector3d(std::sin(0.9 * t), std::cos(1.7 * t), std::sin(2.3 * t + 0.4));
    d.problem.theta_m[j] += h.cwiseProduct(between[j] - d.tau[j]);
  }
  const LmOptions o = at_sigma();
  MotionModel recorded;
  recorded.torque_before = true;
  recorded.torque_between = between;
  const MotionFit fit = calibrate_in_motion(d.problem, d.omega, d.tau, o, recorded);
  expect_lag_recovered(d, fit, h);
  MotionModel sample_before;
  sample_before.torque_before = true;
  const MotionFit missed = calibrate_in_motion(d.problem, d.omega, d.tau, o, sample_before);
  // The ML residuals' squares over n sigma^2: about 1 for the right model
  // (580 degrees of freedom: 1 +- 0.06), far above for the lag that misses the swing.
  const double n_sigma2 = static_cast<double>(d.tau.size()) * kSigma * kSigma;
  EXPECT_NEAR(fit.result.final_cost / n_sigma2, 1.0, 0.25);
  EXPECT_GT(missed.result.final_cost / n_sigma2, 3.0);
  recorded.torque_between.pop_back();
  EXPECT_THROW(calibrate_in_motion(d.problem, d.omega, d.tau, o, recorded), InputError);
}

// The cyclic error considered (MotionModel::cyclic_prior_rad p, not
// estimated): the fit's geometry is that of the model without it, and its
// variance is the plain one plus p^2 times the squared responses of the fit
// to each coefficient a_i, b_i, here by finite differences (readings with
// eps sin(theta_m_i) or eps cos(theta_m_i) added, refitted): to 5 %. The
// joint bound of calib/motion_correction.hpp widens by the same term.
TEST(MotionCorrection, ConsideredCyclicErrorAddsTheFitsResponseToIt) {
  const MotionData d = make_data(400, 23);
  const LmOptions o = at_sigma();
  MotionModel plain, considered;
  considered.cyclic_prior_rad = 2e-5;
  const MotionFit fit0 = calibrate_in_motion(d.problem, d.omega, d.tau, o, plain);
  const MotionFit fit = calibrate_in_motion(d.problem, d.omega, d.tau, o, considered);
  constexpr double kEps = 1e-4;
  std::array<double, kNumParams> added{};
  for (int c = 0; c < 6; ++c) {
    Problem p = d.problem;
    const int i = c % 3;
    for (Eigen::Vector3d& th : p.theta_m) th[i] += kEps * (c < 3 ? std::sin(th[i]) : std::cos(th[i]));
    const MotionFit shifted = calibrate_in_motion(p, d.omega, d.tau, o, plain);
    for (int k = 0; k < kNumParams; ++k) {
      const double g = (shifted.result.geometry.values[k] - fit0.result.geometry.values[k]) / kEps;
      added[static_cast<std::size_t>(k)] += g * g * considered.cyclic_prior_rad * considered.cyclic_prior_rad;
    }
  }
  Robot a;
  a.geometry = d.truth;
  const Samples smp = samples_at(a, disc_poses(a, 400, a.home, 100.0, 23), 0.0, 24);
  const auto bound0 = motion_crb(d.truth, d.problem.free, smp.theta_m, d.omega, d.tau, plain, {}, kSigma);
  const auto bound = motion_crb(d.truth, d.problem.free, smp.theta_m, d.omega, d.tau, considered, {}, kSigma);
  int widened = 0;
  for (int k = 0; k < kNumParams; ++k) {
    if (!d.problem.free[k]) continue;
    const auto K = static_cast<std::size_t>(k);
    EXPECT_NEAR(fit.result.geometry.values[k], fit0.result.geometry.values[k], 1e-6 * fit0.result.sigma[K]) << param_name(k);
    const double expected = std::sqrt(fit0.result.sigma[K] * fit0.result.sigma[K] + added[K]);
    EXPECT_NEAR(fit.result.sigma[K], expected, 0.05 * expected) << param_name(k);
    EXPECT_GE(bound[K], bound0[K] * (1.0 - 1e-9)) << param_name(k);
    EXPECT_NEAR(bound[K], fit.result.sigma[K], 0.05 * fit.result.sigma[K]) << param_name(k);
    widened += fit.result.sigma[K] > 1.1 * fit0.result.sigma[K] ? 1 : 0;
  }
  EXPECT_GT(widened, 0);  // the test has something to check
  for (double v : fit.cyclic) EXPECT_EQ(v, 0.0);  // considered, not estimated
}

// The bound's covariance: its diagonal is motion_crb's squared, it is
// symmetric with zero rows for fixed parameters; with the cyclic error
// estimated under its prior (the Bayesian bound) it lies between the bound
// without that error (a smaller prior only tightens it) and the bound that
// carries it unestimated (an estimator that ignores the error does no
// better than the one that uses its prior), in the PSD sense.
TEST(MotionCorrection, BoundCovarianceLiesBetweenNoErrorAndTheErrorCarried) {
  const MotionData d = make_data(400, 23);
  Robot a;
  a.geometry = d.truth;
  const Samples smp = samples_at(a, disc_poses(a, 400, a.home, 100.0, 23), 0.0, 24);
  MotionModel plain, considered, estimated;
  considered.cyclic_prior_rad = estimated.cyclic_prior_rad = 2e-5;
  estimated.estimate_cyclic = true;
  const auto cov = [&](const MotionModel& m) {
    return motion_crb_covariance(d.truth, d.problem.free, smp.theta_m, d.omega, d.tau, m, {}, kSigma);
  };
  const Eigen::Matrix<double, kNumParams, kNumParams> C0 = cov(plain), Cc = cov(considered), Ce = cov(estimated);
  const auto sigma = motion_crb(d.truth, d.problem.free, smp.theta_m, d.omega, d.tau, estimated, {}, kSigma);
  for (int k = 0; k < kNumParams; ++k) {
    if (!d.problem.free[k]) {
      EXPECT_EQ(Ce.row(k).norm(), 0.0) << param_name(k);
      EXPECT_TRUE(std::isnan(sigma[static_cast<std::size_t>(k)])) << param_name(k);
      continue;
    }
    EXPECT_NEAR(std::sqrt(Ce(k, k)), sigma[static_cast<std::size_t>(k)], 1e-12 * sigma[static_cast<std::size_t>(k)]);
  }
  EXPECT_LT((Ce - Ce.transpose()).norm(), 1e-12 * Ce.norm());
  // Smallest eigenvalue of a difference, relative to the larger matrix's scale.
  const auto least = [](const Eigen::MatrixXd& D, const Eigen::MatrixXd& big) {
    return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(0.5 * (D + D.transpose())).eigenvalues().minCoeff() /
           big.diagonal().maxCoeff();
  };
  EXPECT_GT(least(Ce - C0, Ce), -1e-9);
  EXPECT_GT(least(Cc - Ce, Cc), -1e-9);
  // Strictly between on this path: the data tell a little of the error (2 % of
  // the carried widening), the prior the rest.
  const double widening = (Cc - C0).diagonal().maxCoeff();
  EXPECT_GT((Cc - Ce).diagonal().maxCoeff(), 0.01 * widening);
  EXPECT_GT((Ce - C0).diagonal().maxCoeff(), 0.5 * widening);
  estimated.cyclic_prior_rad = 1e-12;  // a prior that pins the error at 0: no error at all
  EXPECT_LT((cov(estimated) - C0).norm(), 1e-6 * C0.norm());
}

TEST(MotionCorrection, RefusesMismatchedSizesAndOtherCosts) {
  MotionData d = make_data(40, 5);
  LmOptions o;
  d.tau.pop_back();
  EXPECT_THROW(calibrate_in_motion(d.problem, d.omega, d.tau, o), InputError);
  d.tau.push_back(Eigen::Vector3d::Zero());
  o.cost = Cost::kJ2;
  EXPECT_THROW(calibrate_in_motion(d.problem, d.omega, d.tau, o), InputError);
}

// The fit's nuisance Jacobian takes dr / dtheta_m_k of the ML residual from
// the dth_k column of ml_jacobian: theta_m_k and dth_k enter only as their
// sum (eq. 35). Central differences over the readings agree to their own error.
TEST(MotionCorrection, ReadingSensitivitiesAreTheOffsetColumnsOfTheMlJacobian) {
  Geometry g = Geometry::gpm2002_nominal();
  g[kLa2] += 0.4, g[kDth3] -= 0.01, g[kXa3] += 0.3;
  Rng rng(11);
  std::vector<Eigen::Vector3d> theta;
  const Robot r;
  for (int k = 0; k < 20; ++k) {
    const Eigen::Vector2d p = r.home + Eigen::Vector2d(rng.uniform(-60.0, 60.0), rng.uniform(-60.0, 60.0));
    theta.push_back(readings_from_active(g, inverse_kinematics(g, p, r.branch).theta_a) +
                    Eigen::Vector3d(rng.uniform(-1e-3, 1e-3), rng.uniform(-1e-3, 1e-3), rng.uniform(-1e-3, 1e-3)));
  }
  const Eigen::MatrixXd J = ml_jacobian(theta, g);
  for (std::size_t j = 0; j < theta.size(); ++j)
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d a = theta[j], b = theta[j];
      a[k] += 1e-6, b[k] -= 1e-6;
      double ra = 0.0, rb = 0.0;
      ASSERT_TRUE(MlResidual{a}(g.values.data(), &ra) && MlResidual{b}(g.values.data(), &rb));
      const double central = (ra - rb) / 2e-6;
      EXPECT_NEAR(J(static_cast<Eigen::Index>(j), dth(k)), central, 1e-6 * std::abs(central) + 1e-9) << j << " " << k;
    }
}

// The friction element in parallel with the mesh's spring, by hand: stuck,
// it takes half of each torque change (g moves by dtau / (2 T)); at +-1 it
// slides; a reversal moves it back from there at the same rate.
TEST(MotionCorrection, HysteresisStateFollowsHalfTheTorqueUntilItSlides) {
  const double T = 0.5;  // N m
  std::vector<double> tau;
  for (int k = 0; k <= 10; ++k) tau.push_back(0.25 * k);        // 0 .. 2.5 N m: g = tau / (2 T) up to tau = 1
  for (int k = 1; k <= 4; ++k) tau.push_back(2.5 - 0.25 * k);   // back to 1.5 N m
  const std::vector<double> g = hysteresis_state(tau, T);
  ASSERT_EQ(g.size(), tau.size());
  for (int k = 0; k <= 4; ++k) EXPECT_NEAR(g[static_cast<std::size_t>(k)], 0.25 * k, 1e-15) << k;
  for (int k = 4; k <= 10; ++k) EXPECT_EQ(g[static_cast<std::size_t>(k)], 1.0) << k;  // sliding
  EXPECT_NEAR(g[14], 1.0 - 4 * 0.25, 1e-15);  // a reversal of 1 N m = 2 T: from +1 back to 0
  // No threshold: the direction of the last change (a change of 0 keeps it).
  const std::vector<double> sign = hysteresis_state({0.0, 1.0, 1.0, 0.5, 0.7}, 0.0);
  EXPECT_EQ(sign, (std::vector<double>{0.0, 1.0, 1.0, -1.0, 1.0}));
}

// The largest threshold a torque range tells is the one at which a sweep over
// the range takes the element from one end to the other, and no larger.
TEST(MotionCorrection, LargestHysteresisThresholdIsTheOneASweepJustSlides) {
  const double lo = -0.7, hi = 1.3;  // N m
  std::vector<double> tau;
  for (int cycle = 0; cycle < 3; ++cycle)
    for (double t : {lo, hi}) tau.push_back(t);
  const double T = largest_hysteresis_threshold(hi - lo);
  const std::vector<double> g = hysteresis_state(tau, T);
  EXPECT_NEAR(g[tau.size() - 2], -1.0, 1e-12);
  EXPECT_NEAR(g.back(), 1.0, 1e-12);
  const std::vector<double> g_above = hysteresis_state(tau, 1.05 * T);
  EXPECT_LT(g_above.back() - g_above[tau.size() - 2], 2.0 - 0.09) << "a larger threshold never slides";
  MotionModel m;
  m.hysteresis_start_rad = 2e-4, m.hysteresis_compliance_rad_per_Nm = 5e-4;
  EXPECT_DOUBLE_EQ(starting_hysteresis_threshold(m), 0.4);
}

}  // namespace
}  // namespace gpm::calib
