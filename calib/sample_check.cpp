#include "calib/sample_check.hpp"

#include <cmath>

#include <fmt/format.h>

#include "models/errors.hpp"
#include "models/kinematics.hpp"

namespace gpm::calib {

void check_samples(const Problem& problem, const std::vector<std::string>& labels) {
  const size_t n = problem.theta_m.size();
  const size_t p = problem.free.count();
  if (p == 0) {
    throw InputError("--fix: every parameter is fixed; nothing to estimate (free at least one of "
                     "xa1 ... dth3)");
  }
  if (n < p) {
    throw InputError(fmt::format("samples: {} sample{} for {} free parameters; need at least {} "
                                 "(fix more parameters or record more samples)",
                                 n, n == 1 ? "" : "s", p, p));
  }
  // A joint whose reading never changes while another one moves (issue 36.5:
  // a stuck encoder, a column copied over another) leaves its chain's
  // parameters to the other chains' noise: the fit "converged" to a robot
  // that is not one. (All three constant is one pose repeated: the
  // identifiability analysis names that, rank 1.)
  int stuck = -1, moving = 0;
  for (int k = 0; k < kNumChains; ++k) {
    bool moved = false;
    for (size_t j = 1; j < n && !moved; ++j) moved = problem.theta_m[j][k] != problem.theta_m[0][k];
    if (moved) ++moving;
    else if (stuck < 0) stuck = k;
  }
  if (stuck >= 0 && moving > 0) {
    throw InputError(fmt::format(
        "samples: theta_m{} is {} rad in all {} samples: joint {} never moved, so the samples cannot determine its "
        "chain (a stuck encoder or a wrong column? record samples over the workspace)",
        stuck + 1, problem.theta_m[0][stuck], n, stuck + 1));
  }
  const Geometry& g = problem.start;
  auto name = [&](size_t j) {
    return j < labels.size() ? labels[j] : fmt::format("sample {}", j);
  };
  for (size_t j = 0; j < n; ++j) {
    const Eigen::Vector3d& t = problem.theta_m[j];
    if (!t.allFinite()) throw InputError(fmt::format("{}: readings must be finite", name(j)));
    const auto B = elbows(g, active_from_readings(g, t));
    for (int a = 0; a < kNumChains; ++a) {
      for (int b = a + 1; b < kNumChains; ++b) {
        const double d = (B[static_cast<size_t>(a)] - B[static_cast<size_t>(b)]).norm();
        const double hi = g.lb_(a) + g.lb_(b), lo = std::abs(g.lb_(a) - g.lb_(b));
        // The start geometry is only approximate, so a gap of a few mm is
        // normal; a gap beyond kCircleGapTolerance of the link reach means the
        // readings cannot belong to this robot.
        const double tol = kCircleGapTolerance * hi;
        if (d > hi + tol || d < lo - tol) {
          throw InputError(fmt::format(
              "{}: the passive circles of chains {} and {} do not meet at the start geometry "
              "(elbows {:.3f} mm apart, the links reach {:.3f} to {:.3f} mm, tolerance {:.1f} mm): "
              "the readings do not fit this robot (wrong sample, or a start far off: check --model "
              "and the offsets)",
              name(j), a + 1, b + 1, d, lo, hi, tol));
        }
      }
    }
    if (!forward_kinematics(g, active_from_readings(g, t))) {
      throw InputError(fmt::format("{}: the three elbows are collinear at the start geometry (no "
                                   "unique end-effector); drop this sample", name(j)));
    }
  }
}

}  // namespace gpm::calib
