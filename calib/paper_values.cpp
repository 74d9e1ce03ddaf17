#include "calib/paper_values.hpp"

namespace gpm::calib {

Geometry section3_actual() {
  Geometry g = Geometry::gpm2002_nominal();
  g[kXa2] = 433.04;
  g[kXa3] = 433.05;
  g[kYa3] = 499.96;
  g[kLa1] = 244.1; g[kLa2] = 244.2; g[kLa3] = 244.5;
  g[kLb1] = 243.8; g[kLb2] = 244.2; g[kLb3] = 244.2;
  g[kDth1] = g[kDth2] = g[kDth3] = 1.0;
  return g;
}

Geometry table5_actual() {
  Geometry g = Geometry::gpm2002_nominal();
  g[kYa2] = 0.3;
  g[kXa3] = 433.5;
  g[kYa3] = 499.4;
  g[kLa1] = 244.1; g[kLa2] = 244.2; g[kLa3] = 243.5;
  g[kLb1] = 243.8; g[kLb2] = 244.2; g[kLb3] = 244.6;
  g[kDth1] = 0.01; g[kDth2] = -0.01; g[kDth3] = 0.01;
  return g;
}

FreeMask paper_free_mask() {
  FreeMask m;
  m.set();
  m.reset(kXa1);
  m.reset(kYa1);
  m.reset(kXa2);
  return m;
}

Problem table5_problem(const Samples& s, const FreeMask& free) {
  Problem p;
  p.theta_m = s.theta_m;
  p.free = free;
  p.start = Geometry::gpm2002_nominal();
  const Geometry actual = table5_actual();
  for (int i = 0; i < kNumParams; ++i)
    if (!free[static_cast<size_t>(i)]) p.start[i] = actual[i];
  return p;
}

}  // namespace gpm::calib
