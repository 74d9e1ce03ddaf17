// The encoder offsets stated at the home pose (calib/home_reference.hpp).
#include "calib/home_reference.hpp"

#include <cmath>

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

double reducer_error(const std::array<double, 6>& h, int i, double theta_m, double gear_ratio) {
  const auto k = static_cast<std::size_t>(i);
  const double a = harmonic_angle(kReducerHarmonic, theta_m, gear_ratio);
  return h[k] * std::sin(a) + h[k + 3] * std::cos(a);
}

std::optional<HomeOffsets> offsets_at_home(const HomePose& home, const MotionFit& fit, double gear_ratio,
                                           Result& result, std::vector<Eigen::Vector3d>& used,
                                           ReadingModel* reading) {
  const std::array<double, 6>& h = fit.harmonic[kReducerHarmonic];
  const std::array<double, 6>& s = fit.harmonic_sigma[kReducerHarmonic];
  bool estimated = false;
  for (double v : h) estimated = estimated || v != 0.0;
  if (!estimated) return std::nullopt;
  const std::optional<Eigen::Vector3d> r = home_readings(result.geometry, home);
  if (!r) return std::nullopt;
  HomeOffsets out;
  out.reading = *r;
  for (int i = 0; i < 3; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const double e = reducer_error(h, i, (*r)[i], gear_ratio);
    out.moved_rad[i] = e;
    result.geometry[dth(i)] -= e;
    const double a = harmonic_angle(kReducerHarmonic, (*r)[i], gear_ratio);
    const double var = std::isfinite(s[k]) && std::isfinite(s[k + 3])
                           ? std::pow(s[k] * std::sin(a), 2) + std::pow(s[k + 3] * std::cos(a), 2)
                           : 0.0;
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
      "encoder offsets stated at home: the reducer's error twice per motor revolution is referenced to 0 at the home "
      "readings {:.6g}, {:.6g}, {:.6g} rad (the robot zeroed at home; the same link angle at every reading), "
      "dth moved by {:.3g}, {:.3g}, {:.3g} rad",
      moved.reading[0], moved.reading[1], moved.reading[2], -moved.moved_rad[0], -moved.moved_rad[1],
      -moved.moved_rad[2]);
}

}  // namespace gpm::calib
