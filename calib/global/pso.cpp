#include "calib/global/pso.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <vector>

#include "models/rng.hpp"
#include "calib/global/run_log.hpp"
#include "models/errors.hpp"

namespace gpm::calib::global {

RunRecord minimise_pso(const BatchObjective& obj, const PsoSettings& s, const StopRule& stop,
                       uint64_t seed, const ProgressFn& progress) {
  const int n = obj.dim();
  const long np = s.population;
  if (np < 2) throw InputError("PSO: the population must have at least 2 particles");
  if (stop.budget < 1) throw InputError("PSO: the budget must be at least 1 evaluation");
  RunRecord rec;
  RunLog log(stop, progress, rec);
  Rng rng(seed);
  const double inf = std::numeric_limits<double>::infinity();

  std::vector<double> width(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) width[k] = obj.upper[k] - obj.lower[k];
  // Parameter-major: x[k * np + i].
  std::vector<double> x(static_cast<size_t>(n * np)), v(x.size()), pbest(x.size());
  std::vector<double> fx(static_cast<size_t>(np)), fp(fx.size(), inf);
  std::vector<double> gbest(static_cast<size_t>(n));
  long gbest_owner = -1;
  double fg = inf;

  auto init_particle = [&](long i) {
    for (int k = 0; k < n; ++k) {
      x[k * np + i] = rng.uniform(obj.lower[k], obj.upper[k]);
      v[k * np + i] = rng.uniform(-width[k], width[k]);
    }
    fp[i] = inf;
  };
  for (long i = 0; i < np; ++i) init_particle(i);

  int stall = 0;
  while (!log.done()) {
    const long m = std::min(np, log.remaining());
    obj.evaluate(x.data(), np, m, fx.data());
    log.count(m);
    bool improved = false;
    for (long i = 0; i < m; ++i) {
      if (fx[i] < fp[i]) {
        fp[i] = fx[i];
        for (int k = 0; k < n; ++k) pbest[k * np + i] = x[k * np + i];
      }
      if (fx[i] < fg) {
        fg = fx[i];
        gbest_owner = i;
        for (int k = 0; k < n; ++k) gbest[k] = x[k * np + i];
        improved = true;
      }
    }
    log.offer(fg, [&](std::vector<double>& out) { out = gbest; });
    log.end_generation();
    if (m < np || log.done()) break;

    stall = improved ? 0 : stall + 1;
    const double w = s.w_start + (s.w_end - s.w_start) * static_cast<double>(rec.evaluations) /
                                     static_cast<double>(stop.budget);
    for (long i = 0; i < np; ++i) {
      for (int k = 0; k < n; ++k) {
        const size_t at = static_cast<size_t>(k * np + i);
        const double r1 = rng.uniform(), r2 = rng.uniform();
        double vk = w * v[at] + s.c1 * r1 * (pbest[at] - x[at]) + s.c2 * r2 * (gbest[k] - x[at]);
        vk = std::clamp(vk, -width[k], width[k]);
        v[at] = vk;
        x[at] = std::clamp(x[at] + vk, obj.lower[k], obj.upper[k]);
      }
    }
    if (stall >= s.stall_generations) {
      // Re-initialise a random half, never the particle holding Gbest.
      std::vector<long> order(static_cast<size_t>(np));
      std::iota(order.begin(), order.end(), 0L);
      for (long i = np - 1; i > 0; --i)
        std::swap(order[i], order[static_cast<size_t>(rng.below(static_cast<uint64_t>(i + 1)))]);
      long done = 0;
      for (long i : order) {
        if (done == np / 2) break;
        if (i == gbest_owner) continue;
        init_particle(i);
        ++done;
      }
      stall = 0;
    }
  }
  return rec;
}

}  // namespace gpm::calib::global
