#include "calib/monitor/config_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gpm::calib::monitor {
namespace {

// Learnt samples searched around the cursor before the whole memory.
constexpr int kCursorBehind = 8, kCursorAhead = 40;

bool usable(const MapSamples& s, const MapQuery& q, int k) {
  if (q.exclude_halfwidth_s >= 0.0 && std::abs(s.t[k] - q.exclude_t) <= q.exclude_halfwidth_s) return false;
  return s.direction[k] == q.direction;
}

// Index of the nearest usable sample in [lo, hi) and its squared distance.
int nearest_in(const MapSamples& s, const MapQuery& q, int lo, int hi, double& best_d2) {
  int best = -1;
  for (int k = std::max(lo, 0); k < std::min(hi, s.n); ++k) {
    const double d2 = (s.theta[k] - q.theta).squaredNorm();
    if (d2 < best_d2 && usable(s, q, k)) best_d2 = d2, best = k;
  }
  return best;
}

// Interpolates along the segment (k, k + step) when it is one pass and q
// projects onto it; the squared distance to the interpolated point in d2.
bool along_segment(const MapSamples& s, const MapQuery& q, int k, int step, double& d2, double& r) {
  const int k2 = k + step;
  if (k2 < 0 || k2 >= s.n || !usable(s, q, k2) || std::abs(s.t[k2] - s.t[k]) > q.pass_gap_s) return false;
  const Eigen::Vector3d seg = s.theta[k2] - s.theta[k];
  const double len2 = seg.squaredNorm();
  if (!(len2 > 0.0)) return false;
  const double lambda = (q.theta - s.theta[k]).dot(seg) / len2;
  if (lambda < 0.0 || lambda > 1.0) return false;
  d2 = (s.theta[k] + lambda * seg - q.theta).squaredNorm();
  r = s.r[k] + lambda * (s.r[k2] - s.r[k]);
  return true;
}

}  // namespace

bool map_residual(const MapSamples& s, const MapQuery& q, int& cursor, double& r_map) {
  const double radius2 = q.radius_rad * q.radius_rad;
  double d2 = radius2;
  int k = nearest_in(s, q, cursor - kCursorBehind, cursor + kCursorAhead, d2);
  if (k < 0) {
    d2 = radius2;
    k = nearest_in(s, q, 0, s.n, d2);
  }
  if (k < 0) return false;
  cursor = k;
  r_map = s.r[k];
  double best = std::numeric_limits<double>::infinity();
  for (const int step : {-1, 1}) {
    double seg_d2 = 0.0, seg_r = 0.0;
    if (along_segment(s, q, k, step, seg_d2, seg_r) && seg_d2 < best) best = seg_d2, r_map = seg_r;
  }
  return true;
}

}  // namespace gpm::calib::monitor
