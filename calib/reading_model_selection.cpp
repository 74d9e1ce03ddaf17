// Backward selection of a geared drive's reading effects (calib/reading_model_selection.hpp).
#include "calib/reading_model_selection.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <utility>

#include <fmt/format.h>

#include "calib/passive_tension.hpp"
#include "models/errors.hpp"

namespace gpm::calib {
namespace {

// Wald statistic in sigmas of a value (NaN sigma: not estimated).
double sigmas(double value, double sigma) { return std::abs(value) / sigma; }

// The backlash candidates whose flank the samples can tell: a joint's mesh
// torque at least model.backlash_torque_min_Nm in kMinFlankShare of the
// samples, and together (every such joint's flank certain) in
// kMinFlankShareTogether of them, the joint of the fewest certain samples
// given up first (a joint whose mesh carries little torque, e.g. a robot of
// little friction or preload). Together a quarter: a lost motion left out of
// the model costs the geometry far more than the samples whose flank is in
// doubt (docs/PROCEDURES.md, "Backlash on every joint").
constexpr double kMinFlankShare = 0.5;
constexpr double kMinFlankShareTogether = 0.25;
std::array<bool, 3> tellable_backlash(const MotionModel& model, const std::vector<Eigen::Vector3d>& omega,
                                      const std::vector<Eigen::Vector3d>& tau,
                                      const std::vector<Eigen::Vector3d>& alpha, std::array<bool, 3> wanted) {
  const std::size_t n = tau.size();
  const std::vector<Eigen::Vector3d> mesh = mesh_torques(model.load, omega, tau, alpha);
  std::vector<std::array<bool, 3>> certain(n);
  std::array<double, 3> share{};
  for (std::size_t j = 0; j < n; ++j)
    for (int i = 0; i < 3; ++i) {
      certain[j][static_cast<std::size_t>(i)] = std::abs(mesh[j][i]) >= model.backlash_torque_min_Nm;
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
    if (together >= kMinFlankShareTogether || n == 0) return wanted;
    std::size_t weakest = 3;
    for (std::size_t i = 0; i < 3; ++i)
      if (wanted[i] && (weakest == 3 || share[i] < share[weakest])) weakest = i;
    wanted[weakest] = false;
  }
}

// The fit of model with the candidates, or none where it diverges: its
// nuisance passes take the readings where no robot fits them (InputError of
// the samples' check), which a model lacking a larger effect can do.
std::optional<MotionFit> candidates_fit(const Problem& problem, const std::vector<Eigen::Vector3d>& omega,
                                        const std::vector<Eigen::Vector3d>& tau, const LmOptions& options,
                                        const MotionModel& model, const std::vector<Eigen::Vector3d>& alpha) {
  try {
    return calibrate_in_motion(problem, omega, tau, options, model, alpha);
  } catch (const InputError&) {
    return std::nullopt;
  }
}

// The hysteresis candidates the samples can tell: a joint whose mesh torque
// spans enough for the starting threshold (largest_hysteresis_threshold of
// starting_hysteresis_threshold; a torque-off joint's mesh carries its
// rotor's friction only).
std::array<bool, 3> tellable_hysteresis(const MotionModel& model, const std::vector<Eigen::Vector3d>& omega,
                                        const std::vector<Eigen::Vector3d>& tau,
                                        const std::vector<Eigen::Vector3d>& alpha, std::array<bool, 3> wanted) {
  const double threshold = starting_hysteresis_threshold(model);
  const std::vector<Eigen::Vector3d> mesh = mesh_torques(model.load, omega, tau, alpha);
  for (std::size_t i = 0; i < 3 && !tau.empty(); ++i) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const Eigen::Vector3d& t : mesh) lo = std::min(lo, t[static_cast<Eigen::Index>(i)]), hi = std::max(hi, t[static_cast<Eigen::Index>(i)]);
    wanted[i] = wanted[i] && threshold <= largest_hysteresis_threshold(hi - lo);
  }
  return wanted;
}

// Adds to `out` (the selection of the other effects) the hysteresis of the
// joints in `wanted` that its fit shows: each at k sigma of the noise model
// (a loss > 0 only), and all of them together only where they lower the
// fit's chi-square by more than ln n each (the Bayesian information
// criterion: the threshold moves with the loss, a Wald test alone does not
// say whether the fit is better).
void add_hysteresis(const Problem& problem, const std::vector<Eigen::Vector3d>& omega,
                    const std::vector<Eigen::Vector3d>& tau, const LmOptions& options,
                    const std::vector<Eigen::Vector3d>& alpha, const std::array<bool, 3>& wanted, double k,
                    DriveEffectSelection& out) {
  MotionModel with = out.model;
  with.hysteresis = wanted;
  if (!std::ranges::any_of(wanted, std::identity{})) return;
  const char* diverged = "hysteresis: the fit with it diverged (the readings corrected by it no longer fit a robot)";
  std::optional<MotionFit> fitted = candidates_fit(problem, omega, tau, options, with, alpha);
  if (!fitted) return out.dropped.push_back(diverged);
  MotionFit fit = std::move(*fitted);
  std::vector<std::string> shown;
  for (std::size_t i = 0; i < 3; ++i) {
    if (!with.hysteresis[i]) continue;
    const double z = fit.hysteresis[i] / fit.noise_sigma.hysteresis[i];
    const std::string what = fmt::format("hysteresis of joint {} (loss {:.2g} rad, {:.1f} sigma)", i + 1,
                                         2.0 * fit.hysteresis[i], z);
    if (z >= k) shown.push_back(what);
    else out.dropped.push_back(what), with.hysteresis[i] = false;
  }
  const auto q = static_cast<double>(std::ranges::count(with.hysteresis, true));
  if (q == 0.0) return;
  if (with.hysteresis != wanted) {
    fitted = candidates_fit(problem, omega, tau, options, with, alpha);
    if (!fitted) return out.dropped.push_back(diverged);
    fit = std::move(*fitted);
  }
  const double gain = out.fit.chi2 - fit.chi2, penalty = std::log(static_cast<double>(fit.kept.size()));
  if (gain > q * penalty) {
    out.model = with;
    out.fit = std::move(fit);
    out.kept.insert(out.kept.end(), shown.begin(), shown.end());
  } else {
    for (const std::string& h : shown)
      out.dropped.push_back(fmt::format("{}: with it the fit's chi-square changes by {:+.4g}, not down by ln n = {:.3g} "
                                        "per value", h, -gain, penalty));
  }
}

// Every candidate effect of `candidates` added to `model`.
MotionModel with_candidates(MotionModel model, const MotionModel& candidates) {
  model = with_harmonic_candidates(std::move(model), candidates);
  for (std::size_t i = 0; i < 3; ++i) {
    model.backlash[i] = model.backlash[i] || candidates.backlash[i];
  }
  return model;
}

}  // namespace

double pair_sigma_level(double k) { return std::sqrt(-2.0 * std::log(std::erfc(k / std::sqrt(2.0)))); }

MotionModel with_harmonic_candidates(MotionModel model, const MotionModel& candidates) {
  for (std::size_t i = 0; i < 3; ++i) {
    model.joint_harmonic[i] = model.joint_harmonic[i] || candidates.joint_harmonic[i];
    model.motor_harmonic1[i] = model.motor_harmonic1[i] || candidates.motor_harmonic1[i];
    model.motor_harmonic2[i] = model.motor_harmonic2[i] || candidates.motor_harmonic2[i];
    model.cogging[i] = model.cogging[i] || candidates.cogging[i];
  }
  return model;
}

DriveEffectSelection select_drive_effects(const Problem& problem, const std::vector<Eigen::Vector3d>& omega,
                                          const std::vector<Eigen::Vector3d>& tau, const LmOptions& options,
                                          const MotionModel& model, const std::vector<Eigen::Vector3d>& alpha,
                                          const MotionModel& candidates, double k, const MotionFit* fit_of_model) {
  if (std::ranges::any_of(candidates.hysteresis, std::identity{})) {
    const std::array<bool, 3> hysteresis = tellable_hysteresis(model, omega, tau, alpha, candidates.hysteresis);
    // The hysteresis after the others, on the model they chose.
    MotionModel linear = candidates;
    linear.hysteresis = {};
    DriveEffectSelection out = select_drive_effects(problem, omega, tau, options, model, alpha, linear, k, fit_of_model);
    for (std::size_t i = 0; i < 3; ++i)
      if (candidates.hysteresis[i] && !hysteresis[i])
        out.dropped.push_back(fmt::format("hysteresis of joint {} (its mesh torque spans less than 4 x {:.2g} N m: the "
                                          "element would not slide)", i + 1,
                                          starting_hysteresis_threshold(model)));
    add_hysteresis(problem, omega, tau, options, alpha, hysteresis, k, out);
    return out;
  }
  DriveEffectSelection out;
  MotionModel tellable = candidates;
  tellable.backlash = tellable_backlash(model, omega, tau, alpha, candidates.backlash);
  for (std::size_t i = 0; i < 3; ++i)
    if (candidates.backlash[i] && !tellable.backlash[i])
      out.dropped.push_back(fmt::format("backlash of joint {} (its mesh torque too often below {:.2g} N m to tell the flank)",
                                        i + 1, model.backlash_torque_min_Nm));
  out.model = with_candidates(model, tellable);
  const std::optional<MotionFit> fitted = candidates_fit(problem, omega, tau, options, out.model, alpha);
  if (!fitted) {
    out.dropped.push_back("every drive-train candidate: the fit with them diverged (the readings corrected by "
                          "them no longer fit a robot; an effect the model lacks is larger than they are)");
    out.model = model;
    out.fit = fit_of_model ? *fit_of_model : calibrate_in_motion(problem, omega, tau, options, model, alpha);
    return out;
  }
  const MotionFit& all = *fitted;
  const double pair_level = pair_sigma_level(k);
  const std::array<std::string, kHarmonicOrders> order_name{
      "harmonic error once per joint revolution", "harmonic error once per motor revolution",
      "harmonic error twice per motor revolution", fmt::format("cogging ({:g} per motor revolution)", model.cogging_periods)};
  std::array<std::array<bool, 3>*, kHarmonicOrders> orders{&out.model.joint_harmonic, &out.model.motor_harmonic1,
                                                           &out.model.motor_harmonic2, &out.model.cogging};
  bool changed = false;
  for (std::size_t i = 0; i < 3; ++i) {
    if (out.model.backlash[i]) {
      const double z = sigmas(all.backlash[i], all.noise_sigma.backlash[i]);
      const bool keep = z >= k;
      (keep ? out.kept : out.dropped).push_back(fmt::format("backlash of joint {} ({:.1f} sigma)", i + 1, z));
      if (!keep) out.model.backlash[i] = false, changed = true;
    }
    for (std::size_t o = 0; o < kHarmonicOrders; ++o) {
      if (!(*orders[o])[i]) continue;
      const auto& h = all.harmonic[o];
      const auto& hs = all.noise_sigma.harmonic[o];
      const double z = std::hypot(sigmas(h[i], hs[i]), sigmas(h[i + 3], hs[i + 3]));
      const bool keep = z >= pair_level;
      // No 1-sigma: the fit could not tell the pair from the model's other effects (a torque-off joint's
      // cogging is its compliance times the cogging torque).
      const std::string level = std::isfinite(z) ? fmt::format("{:.1f} sigma", z) : "not told from the other effects";
      (keep ? out.kept : out.dropped).push_back(fmt::format("{} of joint {} ({})", order_name[o], i + 1, level));
      if (!keep) (*orders[o])[i] = false, changed = true;
    }
  }
  // Every candidate dropped: out.model is model again (only these flags differ).
  const bool back_to_model = out.model.backlash == model.backlash && out.model.joint_harmonic == model.joint_harmonic &&
                             out.model.motor_harmonic1 == model.motor_harmonic1 &&
                             out.model.motor_harmonic2 == model.motor_harmonic2 && out.model.cogging == model.cogging;
  if (!changed) out.fit = all;
  else if (back_to_model && fit_of_model) out.fit = *fit_of_model;
  else out.fit = calibrate_in_motion(problem, omega, tau, options, out.model, alpha);
  return out;
}

}  // namespace gpm::calib
