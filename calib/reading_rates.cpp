// Joint speeds and accelerations from the readings (calib/reading_rates.hpp).
#include "calib/reading_rates.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "models/kinematics.hpp"

namespace gpm::calib {
namespace {

// Slope at t[j] of the quadratic through the samples a, j-or-b, c (three
// distinct indices, j among them): Lagrange's derivative, second order on any spacing.
Eigen::Vector3d quadratic_slope(const std::vector<double>& t, const std::vector<Eigen::Vector3d>& x, std::size_t a,
                                std::size_t b, std::size_t c, std::size_t j) {
  const double ta = t[a], tb = t[b], tc = t[c], tj = t[j];
  const double la = ((tj - tb) + (tj - tc)) / ((ta - tb) * (ta - tc));
  const double lb = ((tj - ta) + (tj - tc)) / ((tb - ta) * (tb - tc));
  const double lc = ((tj - ta) + (tj - tb)) / ((tc - ta) * (tc - tb));
  return la * x[a] + lb * x[b] + lc * x[c];
}

// The slope of the series x at each sample of each segment [s, e]
// (calib/reading_rates.hpp: centred over +-k samples, one-sided at the ends).
std::vector<Eigen::Vector3d> slopes(const std::vector<double>& t, const std::vector<Eigen::Vector3d>& x,
                                    const std::vector<std::size_t>& segment_start, int k) {
  std::vector<Eigen::Vector3d> d(x.size(), Eigen::Vector3d::Zero());
  const auto ku = static_cast<std::size_t>(k);
  for (std::size_t s_idx = 0; s_idx < segment_start.size(); ++s_idx) {
    const std::size_t s = segment_start[s_idx];
    const std::size_t e = (s_idx + 1 < segment_start.size() ? segment_start[s_idx + 1] : x.size()) - 1;
    if (e == s) continue;  // one sample: nothing to difference
    if (e == s + 1) {      // two samples: their secant
      d[s] = d[e] = (x[e] - x[s]) / (t[e] - t[s]);
      continue;
    }
    for (std::size_t j = s; j <= e; ++j) {
      const std::size_t lo = j >= s + ku ? j - ku : s;
      const std::size_t hi = std::min(j + ku, e);
      if (lo < j && j < hi) {
        d[j] = quadratic_slope(t, x, lo, j, hi, j);  // uniform and lo, hi = j -+ k: the centred secant
      } else if (j == s) {
        const std::size_t far = std::min(j + 2 * ku, e);
        d[j] = quadratic_slope(t, x, j, std::min(j + ku, far - 1), far, j);
      } else {
        const std::size_t far = j >= s + 2 * ku ? j - 2 * ku : s;
        d[j] = quadratic_slope(t, x, far, std::max(j - ku, far + 1), j, j);
      }
    }
  }
  return d;
}

}  // namespace

ReadingRates reading_rates(const std::vector<double>& t, const std::vector<Eigen::Vector3d>& theta_m,
                           const RateOptions& options) {
  if (t.size() != theta_m.size())
    throw std::invalid_argument("reading_rates: as many times as readings needed");
  if (options.span < 1 || options.alpha_span < 0)
    throw std::invalid_argument("reading_rates: span must be >= 1 and alpha_span >= 0");
  const std::size_t n = t.size();
  ReadingRates out;
  if (n == 0) return out;
  std::vector<double> steps;
  for (std::size_t j = 1; j < n; ++j) {
    if (!(t[j] > t[j - 1])) throw std::invalid_argument("reading_rates: times must increase");
    steps.push_back(t[j] - t[j - 1]);
  }
  double max_step = options.max_step_s;
  if (!(max_step > 0.0) && !steps.empty()) {
    std::vector<double> sorted = steps;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
    max_step = 1.5 * sorted[sorted.size() / 2];
  }
  // Segments between gaps; readings unwrapped by 2 pi within each.
  std::vector<std::size_t> segment_start{0};
  std::vector<Eigen::Vector3d> u(n);
  u[0] = theta_m[0];
  for (std::size_t j = 1; j < n; ++j) {
    if (steps[j - 1] > max_step) {
      segment_start.push_back(j);
      u[j] = theta_m[j];
      continue;
    }
    for (int i = 0; i < 3; ++i) {
      u[j][i] = u[j - 1][i] + wrap_pi(theta_m[j][i] - theta_m[j - 1][i]);
    }
  }
  out.omega = slopes(t, u, segment_start, options.span);
  out.alpha = slopes(t, out.omega, segment_start, options.alpha_span > 0 ? options.alpha_span : options.span);
  return out;
}

}  // namespace gpm::calib
