#include "calib/global/de.hpp"

#include <vector>

#include "models/rng.hpp"
#include "calib/global/run_log.hpp"
#include "models/errors.hpp"

namespace gpm::calib::global {

RunRecord minimise_de(const BatchObjective& obj, const DeSettings& s, const StopRule& stop,
                      uint64_t seed, const ProgressFn& progress) {
  const int n = obj.dim();
  const long np = s.population;
  if (np < 4) throw InputError("DE: the population must have at least 4 members");
  if (stop.budget < 1) throw InputError("DE: the budget must be at least 1 evaluation");
  RunRecord rec;
  RunLog log(stop, progress, rec);
  Rng rng(seed);

  // Parameter-major populations: x[k * np + i].
  std::vector<double> x(static_cast<size_t>(n * np)), u(x.size());
  std::vector<double> fx(static_cast<size_t>(np)), fu(fx.size());
  for (long i = 0; i < np; ++i)
    for (int k = 0; k < n; ++k) x[k * np + i] = rng.uniform(obj.lower[k], obj.upper[k]);

  auto column = [&](const std::vector<double>& pop, long i) {
    return [&pop, i, n, np](std::vector<double>& out) {
      out.resize(static_cast<size_t>(n));
      for (int k = 0; k < n; ++k) out[k] = pop[k * np + i];
    };
  };

  // Initial population (only as many members as the budget allows).
  const long m0 = std::min(np, log.remaining());
  obj.evaluate(x.data(), np, m0, fx.data());
  log.count(m0);
  for (long i = 0; i < m0; ++i) log.offer(fx[i], column(x, i));
  log.end_generation();
  if (m0 < np) return rec;

  while (!log.done()) {
    for (long i = 0; i < np; ++i) {
      long r1, r2, r3;
      do r1 = static_cast<long>(rng.below(np)); while (r1 == i);
      do r2 = static_cast<long>(rng.below(np)); while (r2 == i || r2 == r1);
      do r3 = static_cast<long>(rng.below(np)); while (r3 == i || r3 == r1 || r3 == r2);
      const int jrand = static_cast<int>(rng.below(static_cast<uint64_t>(n)));
      for (int k = 0; k < n; ++k) {
        double v = x[k * np + i];
        if (rng.uniform() <= s.cr || k == jrand) {
          v = x[k * np + r1] + s.f * (x[k * np + r2] - x[k * np + r3]);
          if (v < obj.lower[k] || v > obj.upper[k]) v = rng.uniform(obj.lower[k], obj.upper[k]);
        }
        u[k * np + i] = v;
      }
    }
    const long m = std::min(np, log.remaining());
    obj.evaluate(u.data(), np, m, fu.data());
    log.count(m);
    for (long i = 0; i < m; ++i) {
      if (fu[i] <= fx[i]) {
        fx[i] = fu[i];
        for (int k = 0; k < n; ++k) x[k * np + i] = u[k * np + i];
        log.offer(fx[i], column(x, i));
      }
    }
    log.end_generation();
  }
  return rec;
}

}  // namespace gpm::calib::global
