// The drives' friction chosen by the model test (calib/friction_profile.hpp).
#include "calib/friction_profile.hpp"

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

// calibrate_in_motion with each model variant(model, value) of values, the
// fit of the smallest chi2/dof taken.
template <class Variant>
FrictionProfile profile_over(const Problem& problem, const std::vector<Eigen::Vector3d>& omega,
                             const std::vector<Eigen::Vector3d>& tau, const LmOptions& options, const MotionModel& model,
                             const std::vector<Eigen::Vector3d>& alpha, const std::vector<double>& scales, double sigma,
                             Variant variant) {
  FrictionProfile best;
  best.scales = scales;
  double best_value = std::numeric_limits<double>::infinity();
  std::optional<InputError> last_error;
  bool any = false;
  for (double k : scales) {
    const MotionModel m = variant(model, k);
    double value = std::numeric_limits<double>::infinity();
    try {
      MotionFit fit = calibrate_in_motion(problem, omega, tau, options, m, alpha);
      const ModelTest t = model_test(fit.result.geometry, problem.free, fit.corrected, sigma);
      value = t.chi2 / t.dof;
      if (!any || value < best_value) {
        best.fit = std::move(fit);
        best.scale = k;
        best.model = m;
        best_value = value;
        any = true;
      }
    } catch (const InputError& e) {
      last_error = e;
    }
    best.chi2_per_dof.push_back(value);
  }
  if (!any) throw *last_error;
  return best;
}

}  // namespace

FrictionProfile calibrate_friction_profile(const Problem& problem, const std::vector<Eigen::Vector3d>& omega,
                                           const std::vector<Eigen::Vector3d>& tau, const LmOptions& options,
                                           const MotionModel& model, const std::vector<Eigen::Vector3d>& alpha,
                                           const std::vector<double>& scales, double sigma) {
  if (scales.empty()) throw InputError("friction profile: no friction factor to try");
  for (double k : scales)
    if (!(k >= 0.0 && std::isfinite(k)))
      throw InputError(fmt::format("friction profile: factor {} is not a number >= 0", k));
  if (!(sigma > 0.0)) throw InputError(fmt::format("friction profile: reading noise {} rad is not positive", sigma));
  return profile_over(problem, omega, tau, options, model, alpha, scales, sigma, [](MotionModel m, double k) {
    for (std::size_t i = 0; i < 3; ++i) m.load.coulomb_Nm[i] *= k, m.load.viscous_Nm_s[i] *= k;
    return m;
  });
}

FrictionProfile friction_speed_profile(const Problem& problem, const std::vector<Eigen::Vector3d>& omega,
                                       const std::vector<Eigen::Vector3d>& tau, const LmOptions& options,
                                       const MotionModel& model, const std::vector<Eigen::Vector3d>& alpha,
                                       const std::vector<double>& speeds, double sigma) {
  if (speeds.empty()) throw InputError("friction speed profile: no friction speed to try");
  for (double v : speeds)
    if (!(v > 0.0 && std::isfinite(v)))
      throw InputError(fmt::format("friction speed profile: speed {} rad/s is not a number > 0", v));
  if (!(sigma > 0.0))
    throw InputError(fmt::format("friction speed profile: reading noise {} rad is not positive", sigma));
  return profile_over(problem, omega, tau, options, model, alpha, speeds, sigma, [](MotionModel m, double v) {
    m.load.friction_speed_rad_s = v;
    return m;
  });
}

}  // namespace gpm::calib
