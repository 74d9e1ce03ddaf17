// Tests of calib/friction_balance.cpp: the hub's acceleration on a circle
// against the centripetal a = -w^2 r; each drive's friction recovered from
// torques made by the hub's force balance itself (a torque-off drive and two
// that hold the path, every friction different), to rounding without noise
// and within its jackknife 1-sigma with noisy torques; the motors' cogging
// recovered with the frictions where its periods are given (and what it
// leaves in the residual where they are not); a link's force error
// recovered from the residual (sqrt 1.5 of it); a negative friction
// clipped to 0; short or mismatched series refused.
#include "calib/friction_balance.hpp"

#include <cmath>
#include <numbers>
#include <random>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "calib/reading_rates.hpp"
#include "models/errors.hpp"
#include "models/kinematics.hpp"
#include "models/robot.hpp"

namespace gpm::calib {
namespace {

constexpr double kDt = 1e-3;   // s, the samples' interval on the fly
constexpr int kAlphaSpan = 8;  // the procedure's acceleration span at 1 kHz

// Readings of the nominal robot along a hub path hub(t) (mm) sampled every kDt for duration_s.
struct Path {
  Geometry g = Robot{}.geometry;
  std::vector<double> t;
  std::vector<Eigen::Vector3d> theta_m;
};
template <class HubOfTime>
Path path_of(HubOfTime hub, double duration_s) {
  Path p;
  for (double t = 0.0; t < duration_s; t += kDt) {
    p.t.push_back(t);
    p.theta_m.push_back(readings_from_active(p.g, inverse_kinematics(p.g, hub(t)).theta_a));
  }
  return p;
}

// A Lissajous figure round home: every joint's speed changes sign many times, at many speeds.
Path lissajous() {
  return path_of([](double t) { return Eigen::Vector2d(216.5 + 40.0 * std::sin(2.1 * t), 250.0 + 30.0 * std::sin(3.3 * t + 0.4)); },
                 6.0);
}

// The samples' rates and the drive torques (N m) a robot of frictions F, b
// needs along p with drive 1 torque-off, by the balance's own equations
// (calib/friction_balance.hpp): T_1 from drive 1's moment balance at tau_1 = 0,
// T_2 and T_3 from the hub's, then tau_2 and tau_3 from theirs. A motor's
// cogging q_i = A_i sin(a) + B_i cos(a), a = per_rad theta_m_i (cogging:
// A1 A2 A3 B1 B2 B3, N m), acts besides the drive's torque, which is then
// that much less (drive 1's link carries it).
struct Cogging {
  std::array<double, 6> coef{};
  double per_rad = 0.0;
  double at(int i, double theta_m) const {
    const auto k = static_cast<std::size_t>(i);
    return coef[k] * std::sin(per_rad * theta_m) + coef[k + 3] * std::cos(per_rad * theta_m);
  }
};
struct Record {
  std::vector<Eigen::Vector3d> omega, alpha, tau;
  std::vector<Eigen::Vector2d> hub_accel;
  std::vector<Eigen::Vector3d> lever;  // la_i S_i (m): a link force T_i takes -T_i la_i S_i off drive i's torque
};
Record drive_torques(const Path& p, const TransmissionLoad& load, double hub_mass_kg, const Cogging& cogging = {}) {
  RateOptions ro;
  ro.alpha_span = kAlphaSpan;
  const ReadingRates rates = reading_rates(p.t, p.theta_m, ro);
  Record r{rates.omega, rates.alpha, {}, hub_accelerations(p.g, p.t, p.theta_m, kAlphaSpan), {}};
  for (std::size_t j = 0; j < p.t.size(); ++j) {
    const Eigen::Vector3d ta = active_from_readings(p.g, p.theta_m[j]);
    const Eigen::Vector3d tb = forward_kinematics(p.g, ta)->theta_b;
    Eigen::Vector3d lever, load_torque;  // la_i S_i (m); friction and inertia torque of each drive (N m)
    std::array<Eigen::Vector2d, 3> u;
    for (int i = 0; i < 3; ++i) {
      const auto k = static_cast<std::size_t>(i);
      lever[i] = 1e-3 * p.g.la_(i) * std::sin(tb[i] - ta[i]);
      u[k] = Eigen::Vector2d(std::cos(tb[i]), std::sin(tb[i]));
      load_torque[i] = load.coulomb_Nm[k] * std::tanh(r.omega[j][i] / load.friction_speed_rad_s) +
                       load.viscous_Nm_s[k] * r.omega[j][i] + load.inertia_kg_m2[k] * r.alpha[j][i] -
                       cogging.at(i, p.theta_m[j][i]);
    }
    const double T1 = load_torque[0] / lever[0];  // tau_t_1 = -load_torque_1, T = -tau_t / lever
    Eigen::Matrix2d U;
    U << u[1], u[2];
    const Eigen::Vector2d T23 = U.lu().solve(-hub_mass_kg * r.hub_accel[j] - T1 * u[0]);
    r.tau.emplace_back(0.0, load_torque[1] - T23[0] * lever[1], load_torque[2] - T23[1] * lever[2]);
    r.lever.push_back(lever);
  }
  return r;
}

TransmissionLoad drawn_load() {
  TransmissionLoad load;
  load.coulomb_Nm = {0.15, 0.42, 0.6};
  load.viscous_Nm_s = {0.25, 0.08, 0.16};
  load.inertia_kg_m2 = {0.018, 0.017, 0.019};
  load.friction_speed_rad_s = 0.01;
  return load;
}

TEST(FrictionBalance, HubAccelerationOnACircleIsCentripetal) {
  const double w = 2.0, r_mm = 30.0;
  const Path p = path_of([&](double t) { return Eigen::Vector2d(216.5 + r_mm * std::cos(w * t), 250.0 + r_mm * std::sin(w * t)); }, 2.0);
  const std::vector<Eigen::Vector2d> a = hub_accelerations(p.g, p.t, p.theta_m, kAlphaSpan);
  for (std::size_t j = 100; j + 100 < a.size(); j += 97) {
    const Eigen::Vector2d expected = -w * w * 1e-3 * r_mm * Eigen::Vector2d(std::cos(w * p.t[j]), std::sin(w * p.t[j]));
    EXPECT_NEAR((a[j] - expected).norm(), 0.0, 1e-3 * expected.norm()) << "t " << p.t[j];
  }
}

TEST(FrictionBalance, RecoversEachDrivesFrictionFromTheBalancesOwnTorques) {
  const Path p = lissajous();
  const TransmissionLoad truth = drawn_load();
  const Record r = drive_torques(p, truth, 0.475);
  TransmissionLoad told = truth;  // only the inertias and v_F are read
  told.coulomb_Nm = {0.3, 0.3, 0.3};
  told.viscous_Nm_s = {0.15, 0.15, 0.15};
  const BalanceFriction f = friction_from_force_balance(p.g, {p.theta_m, r.omega, r.alpha, r.tau, r.hub_accel}, told, 0.475, 20);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(f.coulomb_Nm[i], truth.coulomb_Nm[i], 1e-9) << "joint " << i + 1;
    EXPECT_NEAR(f.viscous_Nm_s[i], truth.viscous_Nm_s[i], 1e-9) << "joint " << i + 1;
  }
  EXPECT_LT(f.residual_rms_N, 1e-9);
  EXPECT_GT(f.samples, p.t.size() - 40);  // the skipped 20 and the rate stencils' ends at most
}

TEST(FrictionBalance, RecoversTheMotorsCoggingWithTheFriction) {
  const Path p = lissajous();
  const TransmissionLoad truth = drawn_load();
  const Cogging cogging{{0.12, -0.05, 0.08, 0.03, 0.18, -0.1}, 24.0 * 10.0};  // 24 per motor revolution, 10:1
  const Record r = drive_torques(p, truth, 0.475, cogging);
  const BalanceFriction f =
      friction_from_force_balance(p.g, {p.theta_m, r.omega, r.alpha, r.tau, r.hub_accel, cogging.per_rad}, truth, 0.475, 20);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(f.coulomb_Nm[i], truth.coulomb_Nm[i], 1e-9) << "joint " << i + 1;
    EXPECT_NEAR(f.viscous_Nm_s[i], truth.viscous_Nm_s[i], 1e-9) << "joint " << i + 1;
    EXPECT_NEAR(cogging_torque(f, static_cast<int>(i), 0.7, cogging.per_rad), cogging.at(static_cast<int>(i), 0.7), 1e-9);
  }
  for (std::size_t k = 0; k < 6; ++k) EXPECT_NEAR(f.cogging_Nm[k], cogging.coef[k], 1e-9) << "coefficient " << k;
  EXPECT_LT(f.residual_rms_N, 1e-9);
  // Without the periods the ripple is the balance's residual, its frictions off, no cogging stated.
  const BalanceFriction blind = friction_from_force_balance(p.g, {p.theta_m, r.omega, r.alpha, r.tau, r.hub_accel}, truth, 0.475, 20);
  EXPECT_GT(blind.residual_rms_N, 0.1);
  EXPECT_EQ(blind.cogging_Nm, (std::array<double, 6>{}));
  EXPECT_TRUE(std::isnan(blind.cogging_sigma_Nm[0]));
}

TEST(FrictionBalance, NoisyTorquesLandWithinTheJackknifeSigma) {
  const Path p = lissajous();
  const TransmissionLoad truth = drawn_load();
  Record r = drive_torques(p, truth, 0.475);
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.05);  // N m, a drive's current ripple
  for (Eigen::Vector3d& tau : r.tau) tau += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
  const BalanceFriction f = friction_from_force_balance(p.g, {p.theta_m, r.omega, r.alpha, r.tau, r.hub_accel}, truth, 0.475, 20);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_GT(f.coulomb_sigma_Nm[i], 0.0);
    EXPECT_LT(std::abs(f.coulomb_Nm[i] - truth.coulomb_Nm[i]), 4.0 * f.coulomb_sigma_Nm[i]) << "joint " << i + 1;
    EXPECT_LT(std::abs(f.viscous_Nm_s[i] - truth.viscous_Nm_s[i]), 4.0 * f.viscous_sigma_Nm_s[i]) << "joint " << i + 1;
    EXPECT_LT(f.coulomb_sigma_Nm[i], 0.05) << "joint " << i + 1;  // the path determines the friction
  }
}

TEST(FrictionBalance, ALinksForceErrorIsTheResidualOverTheSquareRootOfOneAndAHalf) {
  // Each drive's torque off by the torque of a link force error of 1-sigma
  // 0.4 N: the balance's residual has 1.5 x its variance per component.
  const Path p = lissajous();
  const TransmissionLoad truth = drawn_load();
  Record r = drive_torques(p, truth, 0.475);
  std::mt19937 rng(11);
  const double sigma_T = 0.4;
  std::normal_distribution<double> dT(0.0, sigma_T);
  for (std::size_t j = 0; j < r.tau.size(); ++j)
    for (int i = 0; i < 3; ++i) r.tau[j][i] -= dT(rng) * r.lever[j][i];
  const BalanceFriction f = friction_from_force_balance(p.g, {p.theta_m, r.omega, r.alpha, r.tau, r.hub_accel}, truth, 0.475, 20);
  EXPECT_NEAR(f.residual_rms_N, sigma_T * std::sqrt(1.5), 0.03 * sigma_T);
  EXPECT_NEAR(f.tension_sigma_N, sigma_T, 0.03 * sigma_T);
}

TEST(FrictionBalance, ANegativeFrictionIsClippedToZero) {
  const Path p = lissajous();
  TransmissionLoad truth = drawn_load();
  truth.viscous_Nm_s[1] = -0.05;
  const Record r = drive_torques(p, truth, 0.475);
  const BalanceFriction f = friction_from_force_balance(p.g, {p.theta_m, r.omega, r.alpha, r.tau, r.hub_accel}, truth, 0.475, 20);
  EXPECT_EQ(f.viscous_Nm_s[1], 0.0);
  EXPECT_NEAR(f.coulomb_Nm[1], truth.coulomb_Nm[1], 1e-9);
}

TEST(FrictionBalance, ShortOrMismatchedSeriesRefused) {
  const Path p = path_of([](double t) { return Eigen::Vector2d(216.5 + 20.0 * t, 250.0); }, 0.15);
  const Record r = drive_torques(p, drawn_load(), 0.475);
  try {
    friction_from_force_balance(p.g, {p.theta_m, r.omega, r.alpha, r.tau, r.hub_accel}, drawn_load(), 0.475, 0);
    FAIL() << "150 samples accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("150 usable samples"), std::string::npos) << e.what();
  }
  const std::vector<Eigen::Vector3d> fewer(r.tau.begin(), r.tau.end() - 1);
  EXPECT_THROW(friction_from_force_balance(p.g, {p.theta_m, r.omega, r.alpha, fewer, r.hub_accel}, drawn_load(), 0.475, 0),
               InputError);
}

}  // namespace
}  // namespace gpm::calib
