// Backward selection of a geared drive's reading effects (calib/reading_model_selection.hpp).
#include "calib/reading_model_selection.hpp"

#include <array>
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "calib/passive_tension.hpp"

namespace gpm::calib {
namespace {

// Wald statistic in sigmas of a value (NaN sigma: not estimated).
double sigmas(double value, double sigma) { return std::abs(value) / sigma; }

// The backlash candidates whose flank the samples can tell: a joint's mesh
// torque at least model.backlash_torque_min_Nm in kMinFlankShare of the
// samples, and together (every such joint's flank certain) in kMinFlankShare
// of them, the joint of the fewest certain samples given up first (a joint
// whose mesh carries little torque, e.g. a robot of little friction or preload).
constexpr double kMinFlankShare = 0.5;
std::array<bool, 3> tellable_backlash(const MotionModel& model, const std::vector<Eigen::Vector3d>& omega,
                                      const std::vector<Eigen::Vector3d>& tau,
                                      const std::vector<Eigen::Vector3d>& alpha, std::array<bool, 3> wanted) {
  const std::size_t n = tau.size();
  std::vector<std::array<bool, 3>> certain(n);
  std::array<double, 3> share{};
  for (std::size_t j = 0; j < n; ++j)
    for (int i = 0; i < 3; ++i) {
      const double t = mesh_torque(model.load, i, tau[j][i], omega[j][i], alpha.empty() ? 0.0 : alpha[j][i]);
      certain[j][static_cast<std::size_t>(i)] = std::abs(t) >= model.backlash_torque_min_Nm;
      share[static_cast<std::size_t>(i)] += certain[j][static_cast<std::size_t>(i)] ? 1.0 / static_cast<double>(n) : 0.0;
    }
  for (std::size_t i = 0; i < 3; ++i) wanted[i] = wanted[i] && share[i] >= kMinFlankShare;
  for (;;) {
    double together = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      bool all = true;
      for (std::size_t i = 0; i < 3; ++i) all = all && (!wanted[i] || certain[j][i]);
      together += all ? 1.0 / static_cast<double>(n) : 0.0;
    }
    if (together >= kMinFlankShare || n == 0) return wanted;
    std::size_t weakest = 3;
    for (std::size_t i = 0; i < 3; ++i)
      if (wanted[i] && (weakest == 3 || share[i] < share[weakest])) weakest = i;
    wanted[weakest] = false;
  }
}

// Every candidate effect of `candidates` added to `model`.
MotionModel with_candidates(MotionModel model, const MotionModel& candidates) {
  model = with_harmonic_candidates(std::move(model), candidates);
  for (std::size_t i = 0; i < 3; ++i) model.backlash[i] = model.backlash[i] || candidates.backlash[i];
  return model;
}

}  // namespace

MotionModel with_harmonic_candidates(MotionModel model, const MotionModel& candidates) {
  for (std::size_t i = 0; i < 3; ++i) {
    model.joint_harmonic[i] = model.joint_harmonic[i] || candidates.joint_harmonic[i];
    model.motor_harmonic1[i] = model.motor_harmonic1[i] || candidates.motor_harmonic1[i];
    model.motor_harmonic2[i] = model.motor_harmonic2[i] || candidates.motor_harmonic2[i];
  }
  return model;
}

DriveEffectSelection select_drive_effects(const Problem& problem, const std::vector<Eigen::Vector3d>& omega,
                                          const std::vector<Eigen::Vector3d>& tau, const LmOptions& options,
                                          const MotionModel& model, const std::vector<Eigen::Vector3d>& alpha,
                                          const MotionModel& candidates, double k, const MotionFit* fit_of_model) {
  DriveEffectSelection out;
  MotionModel tellable = candidates;
  tellable.backlash = tellable_backlash(model, omega, tau, alpha, candidates.backlash);
  for (std::size_t i = 0; i < 3; ++i)
    if (candidates.backlash[i] && !tellable.backlash[i])
      out.dropped.push_back(fmt::format("backlash of joint {} (its mesh torque too often below {:.2g} N m to tell the flank)",
                                        i + 1, model.backlash_torque_min_Nm));
  out.model = with_candidates(model, tellable);
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
  // Every candidate dropped: out.model is model again (only these flags differ).
  const bool back_to_model = out.model.backlash == model.backlash && out.model.joint_harmonic == model.joint_harmonic &&
                             out.model.motor_harmonic1 == model.motor_harmonic1 &&
                             out.model.motor_harmonic2 == model.motor_harmonic2;
  if (!changed) out.fit = all;
  else if (back_to_model && fit_of_model) out.fit = *fit_of_model;
  else out.fit = calibrate_in_motion(problem, omega, tau, options, out.model, alpha);
  return out;
}

}  // namespace gpm::calib
