// The joints' speeds and accelerations estimated from the encoder readings
// themselves (a real robot has no link-speed truth; its drives' motor speed
// rings with the transmission): secant differences over the sample series.
//
// Estimator: a centred secant over +-span samples,
//   omega_j = (u_{j+k} - u_{j-k}) / (t_{j+k} - t_{j-k}),   k = span,
// with u the readings unwrapped by 2 pi within a segment; alpha is the same
// secant of the omega series. Why a secant and not a local polynomial: on a
// uniform series the k = 1 secant is the central difference, truncation error
// h^2 / 6 omega'' (O(h^2)) and no lag; its noise from readings quantised to q
// (uniform, independent: q / sqrt(12) each) is q / (sqrt(6) 2 k h), and alpha's
// (u_{j+2k} - 2 u_j + u_{j-2k}) / (2 k h)^2 has sqrt(6) q / (sqrt(12) (2 k h)^2);
// with the acceleration's own span m != k, (u_{j+m+k} - u_{j+m-k} - u_{j-m+k}
// + u_{j-m-k}) / (4 m k h^2) has q / (sqrt(12) 2 m k h^2).
// A local quadratic fit over 2k + 1 samples (Savitzky-Golay) has the same
// centre (no lag); its slope's noise sigma / (h sqrt(k (k+1) (2k+1) / 3)) is
// the central difference's at k = 1 and only 1.1x smaller at k = 2; a
// secant's span trades noise (1/k) against truncation (k^2) with one number.
// The secant of a position difference over 2 k h is also the mean speed over
// that window: the ringing of a stiff transmission faster than 1 / (2 k h)
// averages out, which the drives' instantaneous motor speed does not.
// At the ends of a segment the slope is one-sided: that of the quadratic
// through the end and the samples k and 2k inside ((-3 u_0 + 4 u_k - u_2k) / (2 k h)
// on a uniform series: truncation error (k h)^2 / 3 omega'', noise 3.6x the
// centred one's); near the ends, the quadratic through the clipped stencil
// (Lagrange's derivative, second order on any spacing). alpha there is
// first order (its speeds' O(h^2) errors over h).
// Segments end at gaps in time: an interval longer than
// max_step_s (default 1.5x the median interval) is not differenced across.
// A segment of one sample has speed and acceleration 0 (nothing to difference).
// Unwrapping assumes |omega| h < pi within a segment.
#pragma once

#include <vector>

#include <Eigen/Core>

namespace gpm::calib {

struct RateOptions {
  int span = 1;            // k: the speed's differences span +-k samples (>= 1)
  int alpha_span = 0;      // the acceleration's (differences of the speeds); 0: span
  double max_step_s = 0.0; // intervals longer than this are gaps; <= 0: 1.5x the median interval
};

struct ReadingRates {
  std::vector<Eigen::Vector3d> omega;  // rad/s, each joint's speed at each sample
  std::vector<Eigen::Vector3d> alpha;  // rad/s^2, each joint's acceleration at each sample
};

// Speeds and accelerations of the readings theta_m (rad, any wrap) taken at
// times t (s, increasing); throws std::invalid_argument for sizes that differ,
// times not increasing or span < 1.
ReadingRates reading_rates(const std::vector<double>& t, const std::vector<Eigen::Vector3d>& theta_m,
                           const RateOptions& options = {});

}  // namespace gpm::calib
