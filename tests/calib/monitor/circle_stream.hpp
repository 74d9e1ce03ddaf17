// Test fixture of tests/calib/monitor: encoder readings of a robot moving
// along a circle (centre 216.5, 250 mm, radius 60 mm, period 4 s), sampled at
// the servo rate: readings = IK of the actual robot minus its offsets (paper
// eq. 35), quantised to 2^bits counts per revolution with sim's rounding rule
// (round to the nearest count of q = 2 pi / 2^bits; re-implemented here
// because calib tests cannot link sim), plus optional Gaussian noise.
#pragma once

#include <cmath>
#include <numbers>

#include <Eigen/Core>

#include "models/kinematics.hpp"
#include "models/rng.hpp"

namespace gpm::calib::monitor::testing {

struct CircleStream {
  Eigen::Vector2d centre{216.5, 250.0};
  double radius_mm = 60.0;
  double period_s = 4.0;
  double rate_hz = 1000.0;
  int bits = 17;
  double noise_rad = 0.0;
  // A reading error periodic in the motor angle (gear ratio 10), a function
  // of the configuration: encoder i reads transmission_rad (sin(10 theta_i
  // + i) + 0.5 sin(20 theta_i)) more.
  double transmission_rad = 0.0;
  Rng rng{1};

  // End-effector position at time t.
  Eigen::Vector2d pose(double t) const {
    const double w = 2.0 * std::numbers::pi * t / period_s;
    return centre + radius_mm * Eigen::Vector2d(std::cos(w), std::sin(w));
  }

  // sim/encoder_model.cpp's quantise_reading: nearest count in [0, 2 pi).
  double quantise(double a) const {
    const double two_pi = 2.0 * std::numbers::pi;
    a = std::fmod(a, two_pi);
    if (a < 0.0) a += two_pi;
    if (bits <= 0) return a;
    const double q = two_pi / std::ldexp(1.0, bits);
    const long long counts = 1LL << bits;
    long long c = std::llround(a / q);
    if (c >= counts) c -= counts;
    return static_cast<double>(c) * q;
  }

  // The three readings of robot `actual` at time t.
  Eigen::Vector3d readings(const Geometry& actual, double t) {
    const JointAngles q = inverse_kinematics(actual, pose(t));
    Eigen::Vector3d m;
    for (int i = 0; i < 3; ++i) {
      double a = q.theta_a[i] - actual.dth_(i);
      if (noise_rad > 0.0) a += noise_rad * rng.normal();
      a += transmission_rad * (std::sin(10.0 * q.theta_a[i] + i) + 0.5 * std::sin(20.0 * q.theta_a[i]));
      m[i] = quantise(a);
    }
    return m;
  }
};

}  // namespace gpm::calib::monitor::testing
