// Tests of sim/drive_train.cpp: the drive-train laws against independent facts.
// - backlash: a dead band of total width b; beyond it Hooke's law on |delta| - b/2;
// - stiffness bands: the Harmonic Drive catalogue's torsion formula
//   phi = T1/K1 + (T - T1)/K2 for T1 < T <= T2 (and its other bands), a
//   continuous curve whose slope rises K1 -> K2 -> K3;
// - hysteresis: over a twist cycle +-A the loop of a Prandtl element (yield
//   T_h = K1 H/2 at slip H/2) encloses 4 T_h (A - H/2); the elastic bands and
//   the dead band alone enclose nothing (they store energy, never dissipate);
//   after loading to +-T the twists at zero torque lie H apart (hysteresis loss);
// - transmission error: its Fourier series over one joint revolution has A_j
//   at order 1 and A_m at order n_m N, nothing else (Parseval);
// - friction: breakaway F_c + F_x at rest, F_c + F_x/e at the Stribeck speed,
//   F_c far beyond, rising by mu per N m transmitted, even in speed;
// - applied torque: (1 + delta) x reported, and cogging averages to zero over
//   every motor revolution (a conservative ripple does no net work);
// - draw_drive_train: every draw within the documented plausible range,
//   chains drawn independently.
#include "sim/drive_train.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "sim/effects.hpp"

namespace gpm::sim {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kArcmin = kPi / (180.0 * 60.0);

// Harmonic Drive CSF-20 class (catalogue): T1 7, T2 25 N m; K1..K3 1.3, 1.8, 2.3e4 N m/rad.
DriveChain harmonic() {
  DriveChain c;
  c.stiffness_Nm_per_rad = {1.3e4, 1.8e4, 2.3e4};
  c.band_Nm = {7.0, 25.0};
  return c;
}

DriveChain linear(double k) {
  DriveChain c;
  c.stiffness_Nm_per_rad = {k, k, k};
  return c;
}

TEST(DriveTrain, BacklashIsADeadBandOfItsTotalWidth) {
  DriveChain c = linear(1e4);
  c.backlash_rad = 2e-3;
  for (double delta : {0.0, 5e-4, -9.99e-4, 1e-3, -1e-3}) {
    double s = 0.0;
    EXPECT_EQ(transmission_torque(c, delta, s), 0.0) << delta;
  }
  for (double delta : {1.5e-3, -2.5e-3, 0.01}) {
    double s = 0.0;
    EXPECT_NEAR(transmission_torque(c, delta, s), 1e4 * std::copysign(std::abs(delta) - 1e-3, delta), 1e-9) << delta;
  }
}

TEST(DriveTrain, BandsFollowTheCatalogueTorsionFormula) {
  const DriveChain c = harmonic();
  // Catalogue: phi = T/K1 (T <= T1); T1/K1 + (T - T1)/K2 (T <= T2); T1/K1 + (T2 - T1)/K2 + (T - T2)/K3.
  EXPECT_NEAR(band_twist(c, 5.0), 5.0 / 1.3e4, 1e-15);
  EXPECT_NEAR(band_twist(c, 15.0), 7.0 / 1.3e4 + 8.0 / 1.8e4, 1e-15);
  EXPECT_NEAR(band_twist(c, -30.0), -(7.0 / 1.3e4 + 18.0 / 1.8e4 + 5.0 / 2.3e4), 1e-15);
  // f and f^-1 agree, and the curve is continuous with a slope rising band by band.
  for (double tau = -35.0; tau <= 35.0; tau += 0.37) EXPECT_NEAR(band_torque(c, band_twist(c, tau)), tau, 1e-12);
  const double h = 1e-8;
  const auto slope = [&](double tau) {
    const double e = band_twist(c, tau);
    return (band_torque(c, e + h) - band_torque(c, e - h)) / (2 * h);
  };
  EXPECT_NEAR(slope(3.0), 1.3e4, 1.0);
  EXPECT_NEAR(slope(-15.0), 1.8e4, 1.0);
  EXPECT_NEAR(slope(30.0), 2.3e4, 1.0);
  for (double T : {7.0, 25.0}) {
    const double e = band_twist(c, T);
    EXPECT_NEAR(band_torque(c, e - 1e-12), band_torque(c, e + 1e-12), 1e-6) << "jump at T = " << T;
  }
}

// Loop area (N m rad) of tau_t over one twist cycle delta = A sin(phase), after a first cycle.
double loop_area(const DriveChain& c, double A) {
  const int n = 20000;
  double s = 0.0, area = 0.0;
  double prev_delta = 0.0, prev_tau = transmission_torque(c, 0.0, s);
  for (int k = 1; k <= 2 * n; ++k) {
    const double delta = A * std::sin(2 * kPi * k / n);
    const double tau = transmission_torque(c, delta, s);
    if (k > n) area += 0.5 * (tau + prev_tau) * (delta - prev_delta);
    prev_delta = delta, prev_tau = tau;
  }
  return area;
}

TEST(DriveTrain, HysteresisLoopEnclosesThePrandtlElementsWork) {
  DriveChain c = harmonic();
  const double A = 2e-3;
  EXPECT_NEAR(loop_area(c, A), 0.0, 1e-9) << "the elastic bands dissipate nothing";
  c.backlash_rad = 1e-3;
  EXPECT_NEAR(loop_area(c, A), 0.0, 1e-9) << "nor does the dead band";
  c.backlash_rad = 0.0;
  c.hysteresis_rad = 1.0 * kArcmin;
  const double T_h = 1.3e4 * c.hysteresis_rad / 2;
  EXPECT_NEAR(loop_area(c, A) / (4 * T_h * (A - c.hysteresis_rad / 2)), 1.0, 1e-3);
}

TEST(DriveTrain, HysteresisLossIsTheTwistApartAtZeroTorque) {
  DriveChain c = harmonic();
  c.hysteresis_rad = 1.0 * kArcmin;
  // Load to +20 N m, unload to -20 N m and back: record the twists where the torque crosses zero.
  double s = 0.0, down = NAN, up = NAN, prev_tau = 0.0, prev_delta = 0.0;
  const double amp = band_twist(c, 20.0);
  for (int k = 0; k <= 30000; ++k) {
    const double delta = amp * std::sin(2 * kPi * k / 10000.0);
    const double tau = transmission_torque(c, delta, s);
    if (k > 0 && prev_tau > 0 && tau <= 0) down = prev_delta + (delta - prev_delta) * prev_tau / (prev_tau - tau);
    if (k > 0 && prev_tau < 0 && tau >= 0) up = prev_delta + (delta - prev_delta) * prev_tau / (prev_tau - tau);
    prev_tau = tau, prev_delta = delta;
  }
  EXPECT_NEAR(down - up, c.hysteresis_rad, 1e-3 * c.hysteresis_rad);
}

TEST(DriveTrain, BacklashFlankPushesNeverPulls) {
  DriveChain c = linear(1e4);
  c.backlash_rad = 1e-3;
  c.hysteresis_rad = 4e-4;
  double s = 0.0;
  for (int k = 0; k <= 4000; ++k) {
    const double delta = 3e-3 * std::sin(2 * kPi * k / 1000.0);
    const double tau = transmission_torque(c, delta, s);
    EXPECT_GE(tau * delta, 0.0) << delta;
    if (std::abs(delta) <= 5e-4) {
      EXPECT_EQ(tau, 0.0);
    }
  }
}

TEST(DriveTrain, TransmissionErrorHasItsTwoHarmonicsOnly) {
  DriveChain c;
  c.te_joint_rad = 3e-4, c.te_joint_phase_rad = 0.7;
  c.te_motor_rad = 1e-4, c.te_motor_phase_rad = -1.9;
  const double N = 10.0;
  const int order = 2, n = 4096;
  // Fourier amplitude of harmonic h over one joint revolution.
  const auto amplitude = [&](int h) {
    double a = 0.0, b = 0.0;
    for (int k = 0; k < n; ++k) {
      const double th = 2 * kPi * k / n;
      const double te = transmission_error(c, th, N, order);
      a += 2.0 / n * te * std::cos(h * th), b += 2.0 / n * te * std::sin(h * th);
    }
    return std::hypot(a, b);
  };
  EXPECT_NEAR(amplitude(1), 3e-4, 1e-12);
  EXPECT_NEAR(amplitude(20), 1e-4, 1e-12);
  for (int h : {2, 3, 10, 19, 21, 40}) EXPECT_LT(amplitude(h), 1e-12) << h;
  double power = 0.0;
  for (int k = 0; k < n; ++k) power += std::pow(transmission_error(c, 2 * kPi * k / n, N, order), 2) / n;
  EXPECT_NEAR(power, (9e-8 + 1e-8) / 2, 1e-15);
}

TEST(DriveTrain, FrictionHasBreakawayStribeckDipAndLoadSlope) {
  DriveChain c;
  c.stiction_excess_Nm = 0.2;
  c.stribeck_speed_rad_s = 0.01;
  c.load_friction = 0.05;
  const double Fc = 0.3;
  EXPECT_DOUBLE_EQ(friction_bound(c, Fc, 0.0, 0.0), 0.5);
  EXPECT_NEAR(friction_bound(c, Fc, 0.01, 0.0), 0.3 + 0.2 / std::exp(1.0), 1e-15);
  EXPECT_NEAR(friction_bound(c, Fc, -0.1, 0.0), 0.3, 1e-15);
  EXPECT_DOUBLE_EQ(friction_bound(c, Fc, 0.004, 10.0), friction_bound(c, Fc, -0.004, -10.0));
  EXPECT_NEAR(friction_bound(c, Fc, 0.1, 12.0) - friction_bound(c, Fc, 0.1, 2.0), 0.05 * 10.0, 1e-12);
}

TEST(DriveTrain, AppliedTorqueScalesByTheConstantAndCoggingAveragesOut) {
  DriveChain c;
  c.torque_constant_delta = 0.07;
  c.cogging_Nm = 0.2, c.cogging_phase_rad = 1.1;
  const double N = 10.0;
  const int P = 24, n = 9600;
  // Mean over one motor revolution (2 pi / N of the output-referred angle).
  double mean = 0.0, peak = 0.0;
  for (int k = 0; k < n; ++k) {
    const double tau = applied_torque(c, 5.0, 0.3 + 2 * kPi / N * k / n, N, P);
    mean += tau / n;
    peak = std::max(peak, std::abs(tau - 1.07 * 5.0));
  }
  EXPECT_NEAR(mean, 1.07 * 5.0, 1e-12);
  EXPECT_NEAR(peak, 0.2, 1e-4);
  // Period: 2 pi / (P N) of the output-referred angle.
  EXPECT_NEAR(applied_torque(c, 5.0, 0.3 + 2 * kPi / (P * N), N, P), applied_torque(c, 5.0, 0.3, N, P), 1e-12);
  EXPECT_EQ(applied_torque(DriveChain{}, 5.0, 0.3, N, P), 5.0);
}

// x in [lo, hi] up to round-off of the range's ends (1e-9 relative).
bool within(double x, double lo, double hi) {
  const double tol = 1e-9 * std::max(std::abs(lo), std::abs(hi));
  return x >= lo - tol && x <= hi + tol;
}

TEST(DriveTrain, DrawsStayInTheDocumentedRangesAndDifferBetweenChains) {
  Rng rng(42);
  for (int trial = 0; trial < 200; ++trial) {
    Effects e;
    draw_drive_train(rng, e);
    EXPECT_TRUE(e.drive.any());
    for (const DriveChain& c : e.drive.chain) {
      // SCHEMA.md, "Drive train": the documented plausible ranges.
      const auto K = c.stiffness_Nm_per_rad;
      EXPECT_PRED3(within, c.backlash_rad, 0.3 * kArcmin, 10 * kArcmin);
      EXPECT_PRED3(within, K[0], 0.7e4, 1.3e4);
      EXPECT_PRED3(within, K[1] / K[0], 1.0, 1.4);
      EXPECT_PRED3(within, K[2] / K[1], 1.0, 1.4);
      EXPECT_PRED3(within, c.band_Nm[0], 2.0, 7.0);
      EXPECT_PRED3(within, c.band_Nm[1], 15.0, 25.0);
      EXPECT_PRED3(within, c.hysteresis_rad, 0.1 * kArcmin, 1.0 * kArcmin);
      EXPECT_PRED3(within, c.te_joint_rad, 0.2 * kArcmin, 1.5 * kArcmin);
      EXPECT_PRED3(within, c.te_motor_rad, 0.05 * kArcmin, 0.5 * kArcmin);
      EXPECT_PRED3(within, c.stiction_excess_Nm, 0.05, 0.3);
      EXPECT_PRED3(within, c.stribeck_speed_rad_s, 0.002, 0.05);
      EXPECT_PRED3(within, c.load_friction, 0.02, 0.2);
      EXPECT_PRED3(within, c.torque_constant_delta, -0.1, 0.1);
      EXPECT_PRED3(within, c.cogging_Nm, 0.03, 0.25);
      for (double ph : {c.te_joint_phase_rad, c.te_motor_phase_rad, c.cogging_phase_rad})
        EXPECT_PRED3(within, ph, 0.0, 2 * kPi);
    }
    const auto& ch = e.drive.chain;
    EXPECT_NE(ch[0].backlash_rad, ch[1].backlash_rad);
    EXPECT_NE(ch[1].stiffness_Nm_per_rad[0], ch[2].stiffness_Nm_per_rad[0]);
    EXPECT_NE(ch[0].torque_constant_delta, ch[2].torque_constant_delta);
  }
}

}  // namespace
}  // namespace gpm::sim
