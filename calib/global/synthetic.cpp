#include "calib/global/synthetic.hpp"

#include <algorithm>

#include "calib/global/rng.hpp"
#include "models/errors.hpp"
#include "models/kinematics.hpp"

namespace gpm::calib::global {

Geometry table5_actual() {
  Geometry g = Geometry::gpm2002_nominal();
  g[kYa2] = 0.3;
  g[kXa3] = 433.5;
  g[kYa3] = 499.4;
  g[kLa1] = 244.1;
  g[kLa2] = 244.2;
  g[kLa3] = 243.5;
  g[kLb1] = 243.8;
  g[kLb2] = 244.2;
  g[kLb3] = 244.6;
  g[kDth1] = 0.01;
  g[kDth2] = -0.01;
  g[kDth3] = 0.01;
  return g;
}

Samples workspace_samples(const Robot& robot, int n, uint64_t seed) {
  if (n < 1) throw InputError("workspace samples: need at least 1 sample");
  const Geometry& g = robot.geometry;
  double x0 = g[kXa1], x1 = g[kXa1], y0 = g[kYa1], y1 = g[kYa1];
  for (int i = 1; i < 3; ++i) {
    x0 = std::min(x0, g[xa(i)]);
    x1 = std::max(x1, g[xa(i)]);
    y0 = std::min(y0, g[ya(i)]);
    y1 = std::max(y1, g[ya(i)]);
  }
  Rng rng(seed);
  Samples s;
  s.has_xy = true;
  const long max_tries = 10000L * n;
  for (long tries = 0; static_cast<int>(s.size()) < n; ++tries) {
    if (tries >= max_tries)
      throw InputError("workspace samples: too few reachable points in the workspace");
    const Eigen::Vector2d p(rng.uniform(x0, x1), rng.uniform(y0, y1));
    const Reach r = check_reach(robot, p);
    if (!r.ok) continue;
    s.id.push_back(static_cast<long>(s.size()));
    s.theta_m.push_back(readings_from_active(g, r.q.theta_a));
    s.xy.push_back(p);
  }
  return s;
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

}  // namespace gpm::calib::global
