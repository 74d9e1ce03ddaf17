// Standard test functions in 12 dimensions for the optimiser tests, as batch
// objectives (parameter-major candidates), plus a counter of evaluations.
#pragma once

#include <cmath>
#include <memory>
#include <numbers>

#include "calib/global/objective.hpp"

namespace gpm::calib::global::testing {

inline constexpr int kDim = 12;

// Wraps f(x) of one point into a BatchObjective on [lo, hi]^12 that counts
// every evaluation into *counter.
template <class F>
BatchObjective make_objective(F f, double lo, double hi, std::shared_ptr<long> counter) {
  BatchObjective obj;
  obj.lower.assign(kDim, lo);
  obj.upper.assign(kDim, hi);
  obj.evaluate = [f, counter](const double* x, long stride, long count, double* out) {
    double p[kDim];
    for (long c = 0; c < count; ++c) {
      for (int k = 0; k < kDim; ++k) p[k] = x[k * stride + c];
      out[c] = f(p);
    }
    *counter += count;
  };
  return obj;
}

// Minimum 0 at the origin.
inline double sphere(const double* x) {
  double s = 0;
  for (int k = 0; k < kDim; ++k) s += x[k] * x[k];
  return s;
}

// Minimum 0 at (1, ..., 1).
inline double rosenbrock(const double* x) {
  double s = 0;
  for (int k = 0; k + 1 < kDim; ++k)
    s += 100.0 * std::pow(x[k + 1] - x[k] * x[k], 2) + std::pow(1.0 - x[k], 2);
  return s;
}

// Minimum 0 at the origin; about 10^12 local minima in [-5.12, 5.12]^12.
inline double rastrigin(const double* x) {
  double s = 10.0 * kDim;
  for (int k = 0; k < kDim; ++k) s += x[k] * x[k] - 10.0 * std::cos(2 * std::numbers::pi * x[k]);
  return s;
}

}  // namespace gpm::calib::global::testing
