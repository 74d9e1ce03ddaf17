// The encoder offsets stated at the home pose (calib/home_reference.hpp).
#include "calib/home_reference.hpp"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "models/kinematics.hpp"

namespace gpm::calib {

std::optional<Eigen::Vector3d> home_readings(const Geometry& g, const HomePose& home) {
  const std::optional<JointAngles> q = try_inverse_kinematics(g, home.p, home.branch);
  if (!q) return std::nullopt;
  Eigen::Vector3d r = readings_from_active(g, q->theta_a);
  for (int i = 0; i < 3; ++i) r[i] = wrap_2pi(r[i]);  // as the encoders report them
  return r;
}

ReducerErrors reducer_errors(const MotionFit& fit, const MotionModel& model) {
  ReducerErrors e;
  for (auto& s : e.sigma) s.fill(std::numeric_limits<double>::quiet_NaN());
  e.h[kReducerHarmonic] = fit.harmonic[kReducerHarmonic];
  e.sigma[kReducerHarmonic] = fit.harmonic_sigma[kReducerHarmonic];
  if (estimates_reducer_joint_error(model)) {
    e.h[kJointHarmonic] = fit.cyclic;
    e.sigma[kJointHarmonic] = fit.cyclic_sigma;
  }
  return e;
}

double reducer_error(const ReducerErrors& e, int i, double theta_m, double gear_ratio) {
  const auto k = static_cast<std::size_t>(i);
  double sum = 0.0;
  for (int o = 0; o < kHarmonicOrders; ++o) {
    if (!referenced_at_home(o)) continue;  // not the reducer's (ReducerErrors holds none of it)
    const auto& h = e.h[static_cast<std::size_t>(o)];
    const double a = harmonic_angle(o, theta_m, gear_ratio, 0.0);
    sum += h[k] * std::sin(a) + h[k + 3] * std::cos(a);
  }
  return sum;
}

namespace {

// Variance of e_i at theta_m: sum over the orders of (sa sin)^2 + (sb cos)^2
// (0 for a pair whose 1-sigma is not finite).
double reducer_error_variance(const ReducerErrors& e, int i, double theta_m, double gear_ratio) {
  const auto k = static_cast<std::size_t>(i);
  double var = 0.0;
  for (int o = 0; o < kHarmonicOrders; ++o) {
    if (!referenced_at_home(o)) continue;  // not the reducer's (ReducerErrors holds none of it)
    const auto& s = e.sigma[static_cast<std::size_t>(o)];
    if (!(std::isfinite(s[k]) && std::isfinite(s[k + 3]))) continue;
    const double a = harmonic_angle(o, theta_m, gear_ratio, 0.0);
    var += std::pow(s[k] * std::sin(a), 2) + std::pow(s[k + 3] * std::cos(a), 2);
  }
  return var;
}

}  // namespace

std::optional<HomeOffsets> offsets_at_home(const HomePose& home, const ReducerErrors& e, double gear_ratio,
                                           Result& result, std::vector<Eigen::Vector3d>& used,
                                           ReadingModel* reading) {
  bool estimated = false;
  for (const auto& h : e.h)
    for (double v : h) estimated = estimated || v != 0.0;
  if (!estimated) return std::nullopt;
  const std::optional<Eigen::Vector3d> r = home_readings(result.geometry, home);
  if (!r) return std::nullopt;
  HomeOffsets out;
  out.reading = *r;
  for (int i = 0; i < 3; ++i) {
    out.moved_rad[i] = reducer_error(e, i, (*r)[i], gear_ratio);
    result.geometry[dth(i)] -= out.moved_rad[i];
    const double var = reducer_error_variance(e, i, (*r)[i], gear_ratio);
    if (var > 0.0 && result.covariance) (*result.covariance)(dth(i), dth(i)) += var;
    auto& sd = result.sigma[static_cast<std::size_t>(dth(i))];
    if (var > 0.0 && std::isfinite(sd)) sd = std::sqrt(sd * sd + var);
  }
  for (Eigen::Vector3d& m : used) m += out.moved_rad;
  if (reading)
    for (int i = 0; i < 3; ++i) reading->reducer_home_rad[static_cast<std::size_t>(i)] = (*r)[i];
  return out;
}

std::string offsets_at_home_note(const HomeOffsets& moved) {
  return fmt::format(
      "encoder offsets stated at home: the reducer's errors (twice per motor revolution, and once per joint revolution "
      "where estimated) are referenced to 0 at the home "
      "readings {:.6g}, {:.6g}, {:.6g} rad (the robot zeroed at home; the same link angle at every reading), "
      "dth moved by {:.3g}, {:.3g}, {:.3g} rad",
      moved.reading[0], moved.reading[1], moved.reading[2], -moved.moved_rad[0], -moved.moved_rad[1],
      -moved.moved_rad[2]);
}

}  // namespace gpm::calib
