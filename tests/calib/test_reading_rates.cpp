// Tests of calib/reading_rates.cpp: on a sinusoid the interior rates are
// within the central differences' truncation bounds (h^2 / 6 f''' for the
// speed, (2h)^2 / 12 f'''' for the acceleration) and their error falls 4x when
// h halves; the ends are one-sided, within their
// second-order bound (h^2 / 3 f'''); the
// noise of readings quantised to q is q / (sqrt(6) 2 k h) for the speed and
// q / (4 sqrt(2) (k h)^2) for the acceleration
// (q / (sqrt(12) 2 m h^2) over a span m of its own); a 2 pi wrap and a gap in time
// are not differenced across; bad arguments are refused.
#include "calib/reading_rates.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <gtest/gtest.h>

#include "models/rng.hpp"

namespace {

using gpm::calib::RateOptions;
using gpm::calib::reading_rates;

constexpr double kPi = std::numbers::pi;

// Joint i: A_i sin(w_i t + p_i) + c_i and its derivatives.
struct Sinusoid {
  Eigen::Vector3d a{0.8, 0.5, 1.2}, w{3.0, 5.0, 2.0}, p{0.1, 1.0, 2.0}, c{1.0, 3.0, 5.0};
  Eigen::Vector3d at(double t) const {
    return (a.array() * ((w * t + p).array()).sin() + c.array()).matrix();
  }
  Eigen::Vector3d speed(double t) const { return (a.array() * w.array() * (w * t + p).array().cos()).matrix(); }
  Eigen::Vector3d accel(double t) const {
    return (-a.array() * w.array().square() * (w * t + p).array().sin()).matrix();
  }
  // max over t of |d^n/dt^n| per joint
  Eigen::Vector3d bound(int n) const { return (a.array() * w.array().pow(n)).matrix(); }
};

struct Series {
  std::vector<double> t;
  std::vector<Eigen::Vector3d> x;
};

Series sample(const Sinusoid& f, double h, int n) {
  Series s;
  for (int j = 0; j < n; ++j) s.t.push_back(j * h), s.x.push_back(f.at(j * h));
  return s;
}

// Largest interior error (samples margin..n-1-margin) of speed and acceleration.
std::pair<double, double> interior_error(const Sinusoid& f, double h, int n, int margin) {
  const Series s = sample(f, h, n);
  const auto r = reading_rates(s.t, s.x);
  double eo = 0.0, ea = 0.0;
  for (int j = margin; j < n - margin; ++j) {
    eo = std::max(eo, (r.omega[j] - f.speed(s.t[j])).cwiseAbs().maxCoeff());
    ea = std::max(ea, (r.alpha[j] - f.accel(s.t[j])).cwiseAbs().maxCoeff());
  }
  return {eo, ea};
}

TEST(ReadingRates, SinusoidInteriorWithinTheCentralDifferencesTruncationBound) {
  const Sinusoid f;
  const double h = 1e-3;
  const int n = 3000;
  const Series s = sample(f, h, n);
  const auto r = reading_rates(s.t, s.x);
  ASSERT_EQ(r.omega.size(), s.x.size());
  ASSERT_EQ(r.alpha.size(), s.x.size());
  for (int j = 2; j < n - 2; ++j) {
    for (int i = 0; i < 3; ++i) {
      // omega: (f(t+h) - f(t-h)) / 2h = f' + h^2/6 f''' + ...
      EXPECT_LE(std::abs(r.omega[j][i] - f.speed(s.t[j])[i]), 1.01 * h * h / 6.0 * f.bound(3)[i]) << j;
      // alpha: (f(t+2h) - 2 f(t) + f(t-2h)) / (2h)^2 = f'' + (2h)^2/12 f'''' + ...
      EXPECT_LE(std::abs(r.alpha[j][i] - f.accel(s.t[j])[i]), 1.01 * 4.0 * h * h / 12.0 * f.bound(4)[i]) << j;
    }
  }
}

TEST(ReadingRates, InteriorErrorIsSecondOrder) {
  const Sinusoid f;
  const auto [eo1, ea1] = interior_error(f, 2e-3, 1500, 2);
  const auto [eo2, ea2] = interior_error(f, 1e-3, 3000, 4);
  EXPECT_NEAR(eo2 / eo1, 0.25, 0.02);
  EXPECT_NEAR(ea2 / ea1, 0.25, 0.02);
}

TEST(ReadingRates, EndsAreOneSidedWithinTheirSecondOrderBound) {
  const Sinusoid f;
  const double h = 1e-3;
  const int n = 500;
  const Series s = sample(f, h, n);
  const auto r = reading_rates(s.t, s.x);
  // (-3 u_0 + 4 u_1 - u_2) / 2h = u'(0) - h^2/3 u''' + ... (and its mirror at the end)
  const Eigen::Vector3d first = (-3.0 * s.x[0] + 4.0 * s.x[1] - s.x[2]) / (2.0 * h);
  const Eigen::Vector3d last = (3.0 * s.x[n - 1] - 4.0 * s.x[n - 2] + s.x[n - 3]) / (2.0 * h);
  EXPECT_LT((r.omega[0] - first).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((r.omega[n - 1] - last).cwiseAbs().maxCoeff(), 1e-9);
  for (int j : {0, 1, n - 2, n - 1}) {
    for (int i = 0; i < 3; ++i) {
      EXPECT_LE(std::abs(r.omega[j][i] - f.speed(s.t[j])[i]), 1.01 * h * h / 3.0 * f.bound(3)[i]) << j;
      // alpha from those speeds: their h^2 errors over h, first order.
      EXPECT_LE(std::abs(r.alpha[j][i] - f.accel(s.t[j])[i]), h * f.bound(3)[i] + h * h * f.bound(4)[i]) << j;
    }
  }
}

TEST(ReadingRates, QuantisedReadingsNoiseFollowsTheFormula) {
  // 17-bit readings of a fast ramp plus a sinusoid: the quantisation errors of
  // consecutive samples are independent, uniform over q.
  const double q = 2.0 * kPi / (1 << 17);
  const double h = 1e-3;
  const int n = 40000;
  gpm::Rng rng(7);
  const Eigen::Vector3d offset(rng.uniform(), rng.uniform(), rng.uniform());
  const Eigen::Vector3d ramp(1.37, -2.11, 0.73);  // rad/s: 29, 44, 15 q per sample
  Sinusoid f;
  for (int span : {1, 2}) {
    std::vector<double> t;
    std::vector<Eigen::Vector3d> x, truth_w, truth_a;
    for (int j = 0; j < n; ++j) {
      const double tj = j * h;
      Eigen::Vector3d v = f.at(tj) + ramp * tj + offset;
      for (int i = 0; i < 3; ++i) v[i] = std::fmod(q * std::floor(v[i] / q) + 20.0 * kPi, 2.0 * kPi);
      t.push_back(tj), x.push_back(v), truth_w.push_back(f.speed(tj) + ramp), truth_a.push_back(f.accel(tj));
    }
    const auto r = reading_rates(t, x, RateOptions{.span = span});
    Eigen::Array3d sw = Eigen::Array3d::Zero(), sa = Eigen::Array3d::Zero();
    int m = 0;
    for (int j = 2 * span; j < n - 2 * span; ++j, ++m) {
      sw += (r.omega[j] - truth_w[j]).array().square();
      sa += (r.alpha[j] - truth_a[j]).array().square();
    }
    const double kh = span * h;
    const double expect_w = q / (std::sqrt(6.0) * 2.0 * kh);
    const double expect_a = q / (4.0 * std::sqrt(2.0) * kh * kh);
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(std::sqrt(sw[i] / m) / expect_w, 1.0, 0.03) << "span " << span << " joint " << i;
      EXPECT_NEAR(std::sqrt(sa[i] / m) / expect_a, 1.0, 0.03) << "span " << span << " joint " << i;
    }
  }
}

TEST(ReadingRates, AccelerationSpanOfItsOwnFollowsItsNoiseFormula) {
  // Speeds over +-1 sample, accelerations over +-m of them: four independent
  // readings, (u_{j+m+1} - u_{j+m-1} - u_{j-m+1} + u_{j-m-1}) / (4 m h^2),
  // noise q / (sqrt(12) 2 m h^2); the speeds' noise is unchanged.
  const double q = 2.0 * kPi / (1 << 17);
  const double h = 1e-3;
  const int n = 40000, m = 8;
  const Eigen::Vector3d ramp(1.37, -2.11, 0.73);
  const Sinusoid f;
  std::vector<double> t;
  std::vector<Eigen::Vector3d> x;
  for (int j = 0; j < n; ++j) {
    Eigen::Vector3d v = f.at(j * h) + ramp * (j * h);
    for (int i = 0; i < 3; ++i) v[i] = q * std::floor(v[i] / q);
    t.push_back(j * h), x.push_back(v);
  }
  const auto r = reading_rates(t, x, RateOptions{.span = 1, .alpha_span = m});
  Eigen::Array3d sw = Eigen::Array3d::Zero(), sa = Eigen::Array3d::Zero();
  int count = 0;
  for (int j = m + 1; j < n - m - 1; ++j, ++count) {
    sw += (r.omega[j] - f.speed(t[j]) - ramp).array().square();
    sa += (r.alpha[j] - f.accel(t[j])).array().square();
  }
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(std::sqrt(sw[i] / count) / (q / (std::sqrt(6.0) * 2.0 * h)), 1.0, 0.03) << i;
    EXPECT_NEAR(std::sqrt(sa[i] / count) / (q / (std::sqrt(12.0) * 2.0 * m * h * h)), 1.0, 0.03) << i;
  }
}

TEST(ReadingRates, TwoPiWrapIsNotASpeed) {
  // A ramp through the wrap of [0, 2 pi): the rates are those of the unwrapped ramp.
  const double h = 1e-3;
  const Eigen::Vector3d speed(3.0, -4.0, 0.5);
  std::vector<double> t;
  std::vector<Eigen::Vector3d> x;
  for (int j = 0; j < 4000; ++j) {
    Eigen::Vector3d v = Eigen::Vector3d(6.0, 0.2, 6.2) + speed * (j * h);
    for (int i = 0; i < 3; ++i) v[i] = std::fmod(v[i] + 4.0 * kPi, 2.0 * kPi);
    t.push_back(j * h), x.push_back(v);
  }
  const auto r = reading_rates(t, x);
  for (std::size_t j = 0; j < x.size(); ++j) {
    EXPECT_LT((r.omega[j] - speed).cwiseAbs().maxCoeff(), 1e-9) << j;
    EXPECT_LT(r.alpha[j].cwiseAbs().maxCoeff(), 1e-5) << j;
  }
}

TEST(ReadingRates, GapInTimeIsNotDifferencedAcross) {
  // Two runs of a sinusoid 0.5 s apart, with the robot moved 1 rad in between:
  // each side of the gap is one-sided, nothing of the jump leaks into the rates.
  const Sinusoid f;
  const double h = 1e-3;
  std::vector<double> t;
  std::vector<Eigen::Vector3d> x;
  for (int j = 0; j < 300; ++j) t.push_back(j * h), x.push_back(f.at(j * h));
  for (int j = 0; j < 300; ++j) {
    const double tj = 0.8 + j * h;
    t.push_back(tj), x.push_back(f.at(tj) + Eigen::Vector3d::Constant(1.0));
  }
  const auto r = reading_rates(t, x);
  for (std::size_t j = 0; j < t.size(); ++j) {
    for (int i = 0; i < 3; ++i) {
      EXPECT_LE(std::abs(r.omega[j][i] - f.speed(t[j])[i]), 1.01 * h * h / 3.0 * f.bound(3)[i]) << j;
      EXPECT_LE(std::abs(r.alpha[j][i] - f.accel(t[j])[i]), h * f.bound(3)[i] + h * h * f.bound(4)[i]) << j;
    }
  }
  // The last sample before the gap takes the one-sided slope of the samples before it.
  EXPECT_LT((r.omega[299] - (3.0 * x[299] - 4.0 * x[298] + x[297]) / (2.0 * h)).cwiseAbs().maxCoeff(), 1e-9);
  // A stated max_step longer than the gap differences across it: the jump
  // leaks into the slopes next to it (weight ~ h / 0.5 s of 1 rad: ~4e-3 rad/s).
  const auto across = reading_rates(t, x, RateOptions{.max_step_s = 1.0});
  EXPECT_GT((across.omega[300] - r.omega[300]).cwiseAbs().minCoeff(), 1e-3);
}

TEST(ReadingRates, SingleSampleSegmentsHaveNoRate) {
  const std::vector<double> t{0.0, 1.0, 1.001, 1.002};
  const std::vector<Eigen::Vector3d> x{Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.001, 0, 0),
                                       Eigen::Vector3d(0.002, 0, 0)};
  const auto r = reading_rates(t, x);
  EXPECT_EQ(r.omega[0], Eigen::Vector3d::Zero());
  EXPECT_NEAR(r.omega[2][0], 1.0, 1e-9);
}

TEST(ReadingRates, BadArgumentsAreRefused) {
  const std::vector<Eigen::Vector3d> x(3, Eigen::Vector3d::Zero());
  EXPECT_THROW(reading_rates({0.0, 1.0}, x), std::invalid_argument);
  EXPECT_THROW(reading_rates({0.0, 1.0, 1.0}, x), std::invalid_argument);
  EXPECT_THROW(reading_rates({0.0, 1.0, 2.0}, x, RateOptions{.span = 0}), std::invalid_argument);
  EXPECT_THROW(reading_rates({0.0, 1.0, 2.0}, x, RateOptions{.alpha_span = -1}), std::invalid_argument);
  EXPECT_TRUE(reading_rates({}, {}).omega.empty());
}

}  // namespace
