// The drives' friction chosen by the model test (calib/friction_profile.hpp).
#include "calib/friction_profile.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <fmt/format.h>

#include "calib/model_test.hpp"
#include "models/errors.hpp"

namespace gpm::calib {

std::vector<double> default_friction_scales() {
  std::vector<double> s = {0.0};
  for (int m = -4; m <= 4; ++m) s.push_back(std::pow(2.0, 0.5 * m));
  return s;
}

std::vector<double> default_friction_speeds() {
  std::vector<double> s;
  for (int m = 0; m <= 4; ++m) s.push_back(0.01 * std::pow(10.0, 0.5 * m));
  return s;
}

namespace {

// Pearson's correlation of x and y (0 where either does not vary).
double correlation(const Eigen::VectorXd& x, const Eigen::VectorXd& y) {
  const Eigen::VectorXd dx = x.array() - x.mean(), dy = y.array() - y.mean();
  const double d = dx.norm() * dy.norm();
  return d > 0.0 ? dx.dot(dy) / d : 0.0;
}

}  // namespace

std::vector<double> speeds_told_from_skew(const std::vector<double>& speeds, const std::vector<Eigen::Vector3d>& omega,
                                          const std::array<bool, 3>& skewed, double max_correlation) {
  std::vector<double> told;
  for (double v : speeds) {
    bool ok = true;
    for (int i = 0; i < 3 && ok; ++i) {
      if (!skewed[static_cast<std::size_t>(i)] || omega.empty()) continue;
      Eigen::VectorXd w(static_cast<Eigen::Index>(omega.size()));
      for (std::size_t j = 0; j < omega.size(); ++j) w[static_cast<Eigen::Index>(j)] = omega[j][i];
      ok = std::abs(correlation((w / v).array().tanh().matrix(), w)) <= max_correlation;
    }
    if (ok) told.push_back(v);
  }
  if (told.empty() && !speeds.empty()) told.push_back(*std::ranges::min_element(speeds));
  return told;
}

namespace {

// The fits of a profile as they are made: chi2/dof per grid value (NaN:
// not tried), the best so far and the last error.
template <class Variant>
struct ProfileWalk {
  const Problem& problem;
  const std::vector<Eigen::Vector3d>& omega;
  const std::vector<Eigen::Vector3d>& tau;
  const LmOptions& options;
  const MotionModel& model;
  const std::vector<Eigen::Vector3d>& alpha;
  const std::vector<double>& grid;
  double sigma;
  Variant variant;
  std::vector<double> value = std::vector<double>(grid.size(), std::numeric_limits<double>::quiet_NaN());
  FrictionProfile best{};
  double best_value = std::numeric_limits<double>::infinity();
  bool any = false;
  std::optional<InputError> last_error{};

  // chi2/dof of grid value k, fitted once (known: its fit, already made); inf where the fit fails.
  double at(std::size_t k, const MotionFit* known = nullptr) {
    if (!std::isnan(value[k])) return value[k];
    const MotionModel m = variant(model, grid[k]);
    value[k] = std::numeric_limits<double>::infinity();
    try {
      MotionFit fit = known ? *known : calibrate_in_motion(problem, omega, tau, options, m, alpha);
      const ModelTest t = model_test(fit.result.geometry, problem.free, fit.corrected, sigma);
      value[k] = t.chi2 / t.dof;
      if (!any || value[k] < best_value) {
        best.fit = std::move(fit);
        best.scale = grid[k];
        best.model = m;
        best_value = value[k];
        any = true;
      }
    } catch (const InputError& e) {
      last_error = e;
    }
    return value[k];
  }

  // From grid index k down chi2/dof to the first local minimum along the grid.
  void walk(std::size_t k, const MotionFit* known) {
    double here = at(k, known);
    for (;;) {
      const double left = k > 0 ? at(k - 1) : std::numeric_limits<double>::infinity();
      const double right = k + 1 < grid.size() ? at(k + 1) : std::numeric_limits<double>::infinity();
      if (!(std::min(left, right) < here)) return;
      k = left <= right ? k - 1 : k + 1;
      here = std::min(left, right);
    }
  }

  // The profile: the values tried in the grid's order and the best fit.
  FrictionProfile result() {
    if (!any) throw *last_error;
    FrictionProfile out = std::move(best);
    for (std::size_t k = 0; k < grid.size(); ++k)
      if (!std::isnan(value[k])) out.scales.push_back(grid[k]), out.chi2_per_dof.push_back(value[k]);
    return out;
  }
};

// calibrate_in_motion with each model variant(model, value) of grid (or
// those of the walk from start), the fit of the smallest chi2/dof taken.
template <class Variant>
FrictionProfile profile_over(const Problem& problem, const std::vector<Eigen::Vector3d>& omega,
                             const std::vector<Eigen::Vector3d>& tau, const LmOptions& options, const MotionModel& model,
                             const std::vector<Eigen::Vector3d>& alpha, const std::vector<double>& grid, double sigma,
                             const ProfileStart& start, Variant variant) {
  ProfileWalk<Variant> w{problem, omega, tau, options, model, alpha, grid, sigma, variant};
  std::optional<std::size_t> start_at;
  if (start.value) {
    const auto it = std::find(grid.begin(), grid.end(), *start.value);
    if (it == grid.end()) throw InputError(fmt::format("friction profile: start {} is not a value tried", *start.value));
    start_at = static_cast<std::size_t>(it - grid.begin());
  }
  if (start.walk) {
    if (!start_at) throw InputError("friction profile: a walk needs a start value");
    if (!std::is_sorted(grid.begin(), grid.end()))
      throw InputError("friction profile: a walk from a start needs the values in ascending order");
    w.walk(*start_at, start.known);
  } else if (start_at && start.known) {
    w.at(*start_at, start.known);
  }
  // Every value, or the rest when no fit of the walk succeeded or its minimum is not trusted.
  if (!start.walk || !w.any || !(w.best_value <= start.trust))
    for (std::size_t k = 0; k < grid.size(); ++k) w.at(k);
  return w.result();
}

}  // namespace

FrictionProfile calibrate_friction_profile(const Problem& problem, const std::vector<Eigen::Vector3d>& omega,
                                           const std::vector<Eigen::Vector3d>& tau, const LmOptions& options,
                                           const MotionModel& model, const std::vector<Eigen::Vector3d>& alpha,
                                           const std::vector<double>& scales, double sigma,
                                           const ProfileStart& start) {
  if (scales.empty()) throw InputError("friction profile: no friction factor to try");
  for (double k : scales)
    if (!(k >= 0.0 && std::isfinite(k)))
      throw InputError(fmt::format("friction profile: factor {} is not a number >= 0", k));
  if (!(sigma > 0.0)) throw InputError(fmt::format("friction profile: reading noise {} rad is not positive", sigma));
  return profile_over(problem, omega, tau, options, model, alpha, scales, sigma, start, [](MotionModel m, double k) {
    for (std::size_t i = 0; i < 3; ++i) m.load.coulomb_Nm[i] *= k, m.load.viscous_Nm_s[i] *= k;
    return m;
  });
}

FrictionProfile friction_speed_profile(const Problem& problem, const std::vector<Eigen::Vector3d>& omega,
                                       const std::vector<Eigen::Vector3d>& tau, const LmOptions& options,
                                       const MotionModel& model, const std::vector<Eigen::Vector3d>& alpha,
                                       const std::vector<double>& speeds, double sigma, const ProfileStart& start) {
  if (speeds.empty()) throw InputError("friction speed profile: no friction speed to try");
  for (double v : speeds)
    if (!(v > 0.0 && std::isfinite(v)))
      throw InputError(fmt::format("friction speed profile: speed {} rad/s is not a number > 0", v));
  if (!(sigma > 0.0))
    throw InputError(fmt::format("friction speed profile: reading noise {} rad is not positive", sigma));
  return profile_over(problem, omega, tau, options, model, alpha, speeds, sigma, start, [](MotionModel m, double v) {
    m.load.friction_speed_rad_s = v;
    return m;
  });
}

}  // namespace gpm::calib
