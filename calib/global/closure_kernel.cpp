#include "calib/global/closure_kernel.hpp"

#include <cmath>
#include <limits>

#include "models/errors.hpp"

namespace gpm::calib::global {

SampleTable make_sample_table(const std::vector<Eigen::Vector3d>& theta_m) {
  SampleTable t;
  t.size = static_cast<long>(theta_m.size());
  for (int i = 0; i < 3; ++i) {
    t.cos_m[i].resize(theta_m.size());
    t.sin_m[i].resize(theta_m.size());
    for (size_t j = 0; j < theta_m.size(); ++j) {
      t.cos_m[i][j] = std::cos(theta_m[j][i]);
      t.sin_m[i][j] = std::sin(theta_m[j][i]);
    }
  }
  return t;
}

namespace {

// One instance per cost and block size so the inner loop has no branch.
template <bool kJ1, int B>
void block(const SampleTable& t, const double* __restrict kv, double* __restrict J) {
  const double* xa1 = kv + kKxa1 * B; const double* ya1 = kv + kKya1 * B;
  const double* xa2 = kv + kKxa2 * B; const double* ya2 = kv + kKya2 * B;
  const double* xa3 = kv + kKxa3 * B; const double* ya3 = kv + kKya3 * B;
  const double* lac1 = kv + kKlac1 * B; const double* lac2 = kv + kKlac2 * B;
  const double* lac3 = kv + kKlac3 * B;
  const double* las1 = kv + kKlas1 * B; const double* las2 = kv + kKlas2 * B;
  const double* las3 = kv + kKlas3 * B;
  const double* lb1 = kv + kKlb1 * B; const double* lb2 = kv + kKlb2 * B;
  const double* lb3 = kv + kKlb3 * B;

  double acc[B];
  for (int c = 0; c < B; ++c) acc[c] = 0.0;
  for (long j = 0; j < t.size; ++j) {
    const double c1 = t.cos_m[0][j], s1 = t.sin_m[0][j];
    const double c2 = t.cos_m[1][j], s2 = t.sin_m[1][j];
    const double c3 = t.cos_m[2][j], s3 = t.sin_m[2][j];
#pragma GCC ivdep
    for (int c = 0; c < B; ++c) {
      // Elbows (eq. 30, 41).
      const double b1x = xa1[c] + (lac1[c] * c1 - las1[c] * s1);
      const double b1y = ya1[c] + (las1[c] * c1 + lac1[c] * s1);
      const double b2x = xa2[c] + (lac2[c] * c2 - las2[c] * s2);
      const double b2y = ya2[c] + (las2[c] * c2 + lac2[c] * s2);
      const double b3x = xa3[c] + (lac3[c] * c3 - las3[c] * s3);
      const double b3y = ya3[c] + (las3[c] * c3 + lac3[c] * s3);
      // Radical centre relative to B1 (eq. 32-33, docs/EQUATIONS.md).
      const double d2x = b2x - b1x, d2y = b2y - b1y;
      const double d3x = b3x - b1x, d3y = b3y - b1y;
      const double q1 = lb1[c] * lb1[c], q2 = lb2[c] * lb2[c], q3 = lb3[c] * lb3[c];
      const double r2 = 0.5 * ((d2x * d2x + d2y * d2y) + (q1 - q2));
      const double r3 = 0.5 * ((d3x * d3x + d3y * d3y) + (q1 - q3));
      const double inv_det = 1.0 / (d2x * d3y - d2y * d3x);
      const double ux = (r2 * d3y - r3 * d2y) * inv_det;
      const double uy = (d2x * r3 - d3x * r2) * inv_det;
      // Rows of E2 / E3 (eq. 38, 42).
      const double v2x = ux - d2x, v2y = uy - d2y;
      const double v3x = ux - d3x, v3y = uy - d3y;
      const double p1 = ux * ux + uy * uy, p2 = v2x * v2x + v2y * v2y, p3 = v3x * v3x + v3y * v3y;
      double e1 = p1 - q1, e2 = p2 - q2, e3 = p3 - q3;
      if constexpr (kJ1) {
        // |E1 row i| = |e_i| / (r_i + lb_i) (eq. 36).
        e1 /= std::sqrt(p1) + lb1[c];
        e2 /= std::sqrt(p2) + lb2[c];
        e3 /= std::sqrt(p3) + lb3[c];
      }
      acc[c] += (e1 * e1 + e2 * e2) + e3 * e3;
    }
  }
  const double inf = std::numeric_limits<double>::infinity();
  for (int c = 0; c < B; ++c) J[c] = acc[c] < inf ? acc[c] : inf;  // NaN (collinear) -> inf
}

}  // namespace

void closure_cost_block(Cost cost, const SampleTable& t, const double* kv, double* J) {
  switch (cost) {
    case Cost::kJ1: block<true, kKernelBlock>(t, kv, J); return;
    case Cost::kJ2:
    case Cost::kJ3: block<false, kKernelBlock>(t, kv, J); return;
    case Cost::kML: break;
  }
  throw InputError("the global solvers evaluate j1, j2 and j3 only (not ml)");
}

double closure_cost_single(Cost cost, const SampleTable& t, const double* kv) {
  double J = 0.0;
  switch (cost) {
    case Cost::kJ1: block<true, 1>(t, kv, &J); return J;
    case Cost::kJ2:
    case Cost::kJ3: block<false, 1>(t, kv, &J); return J;
    case Cost::kML: break;
  }
  throw InputError("the global solvers evaluate j1, j2 and j3 only (not ml)");
}

}  // namespace gpm::calib::global
