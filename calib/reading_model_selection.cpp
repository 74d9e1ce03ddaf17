// Backward selection of a geared drive's reading effects (calib/reading_model_selection.hpp).
#include "calib/reading_model_selection.hpp"

#include <cmath>

#include <fmt/format.h>

namespace gpm::calib {
namespace {

// Wald statistic in sigmas of a value (NaN sigma: not estimated).
double sigmas(double value, double sigma) { return std::abs(value) / sigma; }

// Every candidate effect of `candidates` added to `model`.
MotionModel with_candidates(MotionModel model, const MotionModel& candidates) {
  for (std::size_t i = 0; i < 3; ++i) {
    model.backlash[i] = model.backlash[i] || candidates.backlash[i];
    model.joint_harmonic[i] = model.joint_harmonic[i] || candidates.joint_harmonic[i];
    model.motor_harmonic1[i] = model.motor_harmonic1[i] || candidates.motor_harmonic1[i];
    model.motor_harmonic2[i] = model.motor_harmonic2[i] || candidates.motor_harmonic2[i];
  }
  return model;
}

}  // namespace

DriveEffectSelection select_drive_effects(const Problem& problem, const std::vector<Eigen::Vector3d>& omega,
                                          const std::vector<Eigen::Vector3d>& tau, const LmOptions& options,
                                          const MotionModel& model, const std::vector<Eigen::Vector3d>& alpha,
                                          const MotionModel& candidates, double k) {
  DriveEffectSelection out;
  out.model = with_candidates(model, candidates);
  const MotionFit all = calibrate_in_motion(problem, omega, tau, options, out.model, alpha);
  // A pair (a, b) at the two-sided k-sigma level: chi-square(2) > -2 ln(erfc(k / sqrt 2)).
  const double pair_level = std::sqrt(-2.0 * std::log(std::erfc(k / std::sqrt(2.0))));
  const char* order_name[3] = {"once per joint revolution", "once per motor revolution", "twice per motor revolution"};
  std::array<std::array<bool, 3>*, 3> orders{&out.model.joint_harmonic, &out.model.motor_harmonic1,
                                             &out.model.motor_harmonic2};
  bool changed = false;
  for (std::size_t i = 0; i < 3; ++i) {
    if (out.model.backlash[i]) {
      const double z = sigmas(all.backlash[i], all.noise_sigma.backlash[i]);
      const bool keep = z >= k;
      (keep ? out.kept : out.dropped).push_back(fmt::format("backlash of joint {} ({:.1f} sigma)", i + 1, z));
      if (!keep) out.model.backlash[i] = false, changed = true;
    }
    for (std::size_t o = 0; o < 3; ++o) {
      if (!(*orders[o])[i]) continue;
      const auto& h = all.harmonic[o];
      const auto& hs = all.noise_sigma.harmonic[o];
      const double z = std::hypot(sigmas(h[i], hs[i]), sigmas(h[i + 3], hs[i + 3]));
      const bool keep = z >= pair_level;
      (keep ? out.kept : out.dropped)
          .push_back(fmt::format("harmonic error {} of joint {} ({:.1f} sigma)", order_name[o], i + 1, z));
      if (!keep) (*orders[o])[i] = false, changed = true;
    }
  }
  out.fit = changed ? calibrate_in_motion(problem, omega, tau, options, out.model, alpha) : all;
  return out;
}

}  // namespace gpm::calib
