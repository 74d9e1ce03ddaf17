#include "calib/parameterization.hpp"

#include <cmath>

#include <fmt/format.h>

#include "models/errors.hpp"

namespace gpm::calib {

ParamVector to_solver(const Geometry& g, Cost c) {
  ParamVector x = g.values;
  if ((c == Cost::kJ3)) {
    for (int i = 0; i < kNumChains; ++i) {
      x[static_cast<size_t>(la(i))] = g.la_(i) * std::cos(g.dth_(i));  // l_ac (eq. 41)
      x[static_cast<size_t>(dth(i))] = g.la_(i) * std::sin(g.dth_(i));  // l_as
    }
  }
  return x;
}

Geometry from_solver(const ParamVector& x, Cost c) {
  Geometry g;
  g.values = x;
  if ((c == Cost::kJ3)) {
    for (int i = 0; i < kNumChains; ++i) {
      const double lac = x[static_cast<size_t>(la(i))], las = x[static_cast<size_t>(dth(i))];
      g[la(i)] = std::hypot(lac, las);   // eq. 44 (docs/EQUATIONS.md)
      g[dth(i)] = std::atan2(las, lac);  // eq. 44 (docs/EQUATIONS.md): two-argument atan2
    }
  }
  return g;
}

Eigen::Matrix<double, kNumParams, kNumParams> geometry_jacobian(const ParamVector& x, Cost c) {
  Eigen::Matrix<double, kNumParams, kNumParams> T =
      Eigen::Matrix<double, kNumParams, kNumParams>::Identity();
  if (!(c == Cost::kJ3)) return T;
  for (int i = 0; i < kNumChains; ++i) {
    const double lac = x[static_cast<size_t>(la(i))], las = x[static_cast<size_t>(dth(i))];
    const double r2 = lac * lac + las * las, r = std::sqrt(r2);
    T(la(i), la(i)) = lac / r;
    T(la(i), dth(i)) = las / r;
    T(dth(i), la(i)) = -las / r2;
    T(dth(i), dth(i)) = lac / r2;
  }
  return T;
}

void check_free_set(const FreeMask& free, Cost c) {
  if (!(c == Cost::kJ3)) return;
  for (int i = 0; i < kNumChains; ++i) {
    if (free.test(static_cast<size_t>(la(i))) != free.test(static_cast<size_t>(dth(i)))) {
      throw InputError(fmt::format(
          "--cost j3: la{0} and dth{0} must be both free or both fixed (J3 estimates l_ac = la "
          "cos dth and l_as = la sin dth, eq. 41-42); free or fix both, or use --cost ml or j2",
          i + 1));
    }
  }
}

}  // namespace gpm::calib
