// Tests of sim/encoder_error.cpp (and its use by read_encoders in
// sim/twin.cpp), against independent facts:
// - at gear ratio 1 without harmonics the error is the once-per-revolution
//   sine of sim/effects.hpp, to the bit;
// - an error of k cycles per motor revolution repeats k N times per joint
//   revolution (N the gear ratio): it is periodic in 2 pi / N, and the
//   discrete Fourier transform over a joint revolution (orthogonality of
//   sines) gives each harmonic's amplitude and phase at k N and nothing at
//   once per joint revolution;
// - the twin's reading over a whole joint revolution is that error on the
//   grid of 2^bits N counts per joint revolution;
// - latch jitter: the offset has mean skew and standard deviation sigma; the
//   twin's reading of a joint turning at w is off by -dt w; the same seed
//   gives the same readings; no jitter draws nothing.
#include "sim/encoder_error.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "models/kinematics.hpp"
#include "sim/effects.hpp"
#include "sim/twin.hpp"

namespace gpm::sim {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

Effects with_harmonics(double ratio) {
  Effects e;
  e.gear_ratio = ratio;
  e.encoder_cyclic_rad = {2e-5, 3e-5, 1e-5};
  e.encoder_phase_rad = {0.3, 2.0, 4.5};
  e.encoder_harmonics[0] = EncoderHarmonic{2, {4e-6, 5e-6, 6e-6}, {1.0, 5.0, 0.1}};
  e.encoder_harmonics[1] = EncoderHarmonic{4, {1e-6, 2e-6, 3e-6}, {2.5, 0.7, 3.3}};
  return e;
}

TEST(EncoderError, AtRatioOneWithoutHarmonicsIsTheOncePerRevolutionSine) {
  Effects e;
  e.encoder_cyclic_rad = {2e-5, 0.0, 1e-3};
  e.encoder_phase_rad = {0.3, 2.0, 4.5};
  for (int i = 0; i < 3; ++i)
    for (double r = -7.0; r < 7.0; r += 0.01)
      EXPECT_EQ(encoder_angle_error(e, i, r), cyclic_error(e.encoder_cyclic_rad[i], e.encoder_phase_rad[i], r));
}

TEST(EncoderError, RepeatsGearRatioTimesPerJointRevolution) {
  const Effects e = with_harmonics(10.0);
  for (int i = 0; i < 3; ++i)
    for (double r = 0.0; r < kTwoPi; r += 0.013)
      EXPECT_NEAR(encoder_angle_error(e, i, r + kTwoPi / 10.0), encoder_angle_error(e, i, r), 1e-15);
}

// Amplitude and phase of the m-cycles-per-joint-revolution component of encoder i's error.
std::pair<double, double> fourier(const Effects& e, int i, int m) {
  const int n = 8192;
  double s = 0.0, c = 0.0;
  for (int j = 0; j < n; ++j) {
    const double r = kTwoPi * j / n;
    const double err = encoder_angle_error(e, i, r);
    s += err * std::sin(m * r) * 2.0 / n;
    c += err * std::cos(m * r) * 2.0 / n;
  }
  // A sin(m r + phi) = A cos(phi) sin(m r) + A sin(phi) cos(m r)
  return {std::hypot(s, c), std::atan2(c, s)};
}

TEST(EncoderError, EachHarmonicSitsAtItsOrderTimesTheRatioPerJointRevolution) {
  const Effects e = with_harmonics(10.0);
  for (int i = 0; i < 3; ++i) {
    const size_t k = static_cast<size_t>(i);
    const auto [a1, p1] = fourier(e, i, 10);
    EXPECT_NEAR(a1, e.encoder_cyclic_rad[k], 1e-12);
    EXPECT_NEAR(wrap_pi(p1 - e.encoder_phase_rad[k]), 0.0, 1e-6);
    for (const EncoderHarmonic& h : {e.encoder_harmonics[0], e.encoder_harmonics[1]}) {
      const auto [a, p] = fourier(e, i, 10 * h.order);
      EXPECT_NEAR(a, h.amplitude_rad[k], 1e-12) << "order " << h.order;
      EXPECT_NEAR(wrap_pi(p - h.phase_rad[k]), 0.0, 1e-6) << "order " << h.order;
    }
    EXPECT_LT(fourier(e, i, 1).first, 1e-15) << "nothing once per joint revolution";
  }
}

// A twin at rest whose joint angles are set directly (twin_sense reads them).
struct Bench {
  TwinModel model;
  TwinState state;
  Bench(const TwinConfig& c, unsigned long long seed) : model(Robot{}, c), state(model, seed) {}
  // Readings with motor angle theta and speed w on every joint.
  Eigen::Vector3d read(double theta, double w) {
    for (int i = 0; i < 3; ++i) {
      state.data->qpos[model.qpos_m[i]] = theta;
      state.data->qvel[model.dof_m[i]] = w;
    }
    twin_sense(model, state);
    return state.last.readings;
  }
};

TEST(EncoderError, TwinReadsTheMotorHarmonicsOnTheJointCountGrid) {
  TwinConfig c;
  c.encoder.bits = 17;
  c.effects = with_harmonics(10.0);
  Bench b(c, 1);
  const Geometry& g = b.model.actual().geometry;
  const double q = kTwoPi / (131072.0 * 10.0);  // one count of the joint reading
  double worst = 0.0;
  for (double x = 0.0; x < kTwoPi; x += 0.0007) {
    const Eigen::Vector3d r = b.read(x, 0.0);
    for (int i = 0; i < 3; ++i) {
      ASSERT_NEAR(r[i] / q, std::round(r[i] / q), 1e-6) << "whole counts of 2^17 x 10 per joint revolution";
      const double ideal = x - g.dth_(i);
      const double want = ideal + encoder_angle_error(c.effects, i, ideal);
      worst = std::max(worst, std::abs(wrap_pi(r[i] - want)));
    }
  }
  EXPECT_LE(worst, 0.5 * q * (1 + 1e-6)) << "the reading is the error within half a joint count";
  EXPECT_GT(worst, 0.4 * q);
}

TEST(EncoderError, LatchOffsetHasTheSkewAsMeanAndTheJitterAsSpread) {
  Effects e;
  e.encoder_skew_s = {0.0, 5e-5, 1e-4};
  e.encoder_jitter_s = {1e-6, 0.0, 2e-5};
  Rng rng(7);
  const int n = 40000;
  double sum[3] = {}, sum2[3] = {};
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < 3; ++i) {
      const double d = latch_offset_s(e, i, rng) - e.encoder_skew_s[static_cast<size_t>(i)];
      sum[i] += d, sum2[i] += d * d;
    }
  for (int i = 0; i < 3; ++i) {
    const double sigma = e.encoder_jitter_s[static_cast<size_t>(i)];
    EXPECT_NEAR(sum[i] / n, 0.0, 5.0 * sigma / std::sqrt(n) + 1e-20) << i;
    EXPECT_NEAR(std::sqrt(sum2[i] / n), sigma, 0.02 * sigma + 1e-20) << i;
  }
}

TEST(EncoderError, TwinReadingOfATurningJointIsOffBySpeedTimesTheLatchTime) {
  TwinConfig c;
  c.encoder.bits = 0;
  c.effects.encoder_jitter_s = {1e-4, 5e-5, 0.0};
  c.effects.encoder_skew_s = {0.0, 0.0, 1e-4};
  Bench a(c, 3), same(c, 3);
  const Geometry& g = a.model.actual().geometry;
  const double w = 2.0;  // rad/s
  const int n = 20000;
  double sum[3] = {}, sum2[3] = {};
  for (int k = 0; k < n; ++k) {
    const double x = 1.0 + 1e-4 * k;
    const Eigen::Vector3d r = a.read(x, w);
    ASSERT_EQ(r, same.read(x, w)) << "bit-reproducible from the seed";
    for (int i = 0; i < 3; ++i) {
      const double dt = -wrap_pi(r[i] - (x - g.dth_(i))) / w;  // reading = theta - dt w
      sum[i] += dt, sum2[i] += dt * dt;
    }
  }
  for (int i = 0; i < 3; ++i) {
    const size_t k = static_cast<size_t>(i);
    const double mean = sum[i] / n, sd = std::sqrt(std::max(0.0, sum2[i] / n - mean * mean));
    EXPECT_NEAR(mean, c.effects.encoder_skew_s[k], 5.0 * c.effects.encoder_jitter_s[k] / std::sqrt(n) + 1e-12) << i;
    EXPECT_NEAR(sd, c.effects.encoder_jitter_s[k], 0.03 * c.effects.encoder_jitter_s[k] + 1e-9) << i;
  }
}

TEST(EncoderError, NoJitterDrawsNothingFromTheTwinsNoise) {
  TwinConfig c;
  c.effects = with_harmonics(10.0);  // errors, but no jitter and no noise
  Bench b(c, 11);
  for (double x = 0.0; x < 1.0; x += 0.1) b.read(x, 3.0);
  Rng fresh(11);
  EXPECT_EQ(b.state.noise.rng(), fresh());
}

// Draws of draw_encoder_and_geometry stay within the ranges stated in
// scenarios/SCHEMA.md (motor-side arcsec divided by the gear ratio), differ
// between chains, repeat with the seed and leave the gear ratio, the
// once-per-revolution error and every other effect alone.
TEST(EncoderError, RandomDrawsStayInTheirRangesAndDifferBetweenChains) {
  constexpr double as = std::numbers::pi / (180.0 * 3600.0);
  for (double ratio : {1.0, 10.0}) {
    for (std::uint64_t seed = 1; seed <= 200; ++seed) {
      Effects e;
      e.gear_ratio = ratio;
      Rng rng(seed), again(seed);
      draw_encoder_and_geometry(rng, e);
      Effects e2;
      e2.gear_ratio = ratio;
      draw_encoder_and_geometry(again, e2);
      ASSERT_EQ(e.encoder_jitter_s, e2.encoder_jitter_s) << "seeded";
      ASSERT_EQ(e.mjcf.hub_pin_m, e2.mjcf.hub_pin_m) << "seeded";
      EXPECT_EQ(e.encoder_cyclic_rad, Effects{}.encoder_cyclic_rad) << "the randomized preset's, not drawn here";
      EXPECT_EQ(e.gear_ratio, ratio) << "a data-sheet value, not drawn";
      EXPECT_FALSE(e.mjcf.compliant() || e.mjcf.loose());
      for (const auto& p : e.mjcf.hub_pin_m) EXPECT_LE(std::hypot(p[0], p[1]), 20e-6 * (1 + 1e-12));
      EXPECT_NE(e.mjcf.hub_pin_m[0], e.mjcf.hub_pin_m[1]);
      EXPECT_EQ(e.thermal.rise_K, 0.0) << "the warm-up itself is not this draw's";
      for (size_t k = 0; k < 3; ++k) {
        EXPECT_GE(e.encoder_jitter_s[k], 0.05e-6);
        EXPECT_LE(e.encoder_jitter_s[k], 2e-6);
        EXPECT_EQ(e.encoder_harmonics[0].order, 2);
        EXPECT_EQ(e.encoder_harmonics[1].order, 4);
        EXPECT_LE(e.encoder_harmonics[0].amplitude_rad[k] * ratio, 6.0 * as * (1 + 1e-12));
        EXPECT_LE(e.encoder_harmonics[1].amplitude_rad[k] * ratio, 3.0 * as * (1 + 1e-12));
        EXPECT_GE(e.encoder_harmonics[1].amplitude_rad[k] * ratio, 0.5 * as * (1 - 1e-12));
      }
      EXPECT_NE(e.encoder_harmonics[0].amplitude_rad[0], e.encoder_harmonics[0].amplitude_rad[1]);
      EXPECT_NE(e.encoder_jitter_s[1], e.encoder_jitter_s[2]);
      EXPECT_NE(e.encoder_harmonics[0].phase_rad[0], e.encoder_harmonics[0].phase_rad[2]);
      const double alpha_b = e.thermal.base_expansion_per_K.value_or(0.0);
      EXPECT_TRUE(alpha_b >= 10e-6 && alpha_b <= 13e-6) << alpha_b;
      const double tau_b = e.thermal.base_time_constant_s.value_or(0.0);
      EXPECT_TRUE(tau_b >= 1800.0 && tau_b <= 7200.0) << tau_b;
    }
  }
}

}  // namespace
}  // namespace gpm::sim
