#include "calib/global/pso.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <vector>

#include "models/rng.hpp"
#include "calib/global/run_log.hpp"
#include "models/errors.hpp"

namespace gpm::calib::global {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The swarm: positions x, velocities v and personal bests pbest (fp), all
// parameter-major (x[k * np + i]), the global best gbest (fg, held by
// particle gbest_owner), the box widths and the run's random stream.
struct Swarm {
  Swarm(const BatchObjective& obj, long population, uint64_t seed)
      : n(obj.dim()), np(population), rng(seed), width(static_cast<size_t>(n)),
        x(static_cast<size_t>(n * np)), v(x.size()), pbest(x.size()), fx(static_cast<size_t>(np)),
        fp(fx.size(), kInf), gbest(static_cast<size_t>(n)) {
    for (int k = 0; k < n; ++k) width[k] = obj.upper[k] - obj.lower[k];
  }
  const int n;
  const long np;
  Rng rng;
  std::vector<double> width, x, v, pbest, fx, fp, gbest;
  long gbest_owner = -1;
  double fg = kInf;
};

// Throws InputError for a population or budget PSO cannot run with.
void check_settings(const PsoSettings& s, const StopRule& stop) {
  if (s.population < 2) throw InputError("PSO: the population must have at least 2 particles");
  if (stop.budget < 1) throw InputError("PSO: the budget must be at least 1 evaluation");
}

// Particle i at a random position in the box, a random velocity within the
// box width and no personal best.
void init_particle(const BatchObjective& obj, Swarm& w, long i) {
  for (int k = 0; k < w.n; ++k) {
    w.x[k * w.np + i] = w.rng.uniform(obj.lower[k], obj.upper[k]);
    w.v[k * w.np + i] = w.rng.uniform(-w.width[k], w.width[k]);
  }
  w.fp[i] = kInf;
}

// The personal and global bests after the first m particles' values fx;
// true when the global best improved.
bool update_bests(Swarm& w, long m) {
  const int n = w.n;
  const long np = w.np;
  bool improved = false;
  for (long i = 0; i < m; ++i) {
    if (w.fx[i] < w.fp[i]) {
      w.fp[i] = w.fx[i];
      for (int k = 0; k < n; ++k) w.pbest[k * np + i] = w.x[k * np + i];
    }
    if (w.fx[i] < w.fg) {
      w.fg = w.fx[i];
      w.gbest_owner = i;
      for (int k = 0; k < n; ++k) w.gbest[k] = w.x[k * np + i];
      improved = true;
    }
  }
  return improved;
}

// One move of every particle with inertia w_inertia (eq. 45), velocities
// limited to the box width, positions put on the box's border.
void move_swarm(const BatchObjective& obj, const PsoSettings& s, double w_inertia, Swarm& w) {
  for (long i = 0; i < w.np; ++i) {
    for (int k = 0; k < w.n; ++k) {
      const size_t at = static_cast<size_t>(k * w.np + i);
      const double r1 = w.rng.uniform(), r2 = w.rng.uniform();
      double vk = w_inertia * w.v[at] + s.c1 * r1 * (w.pbest[at] - w.x[at]) + s.c2 * r2 * (w.gbest[k] - w.x[at]);
      vk = std::clamp(vk, -w.width[k], w.width[k]);
      w.v[at] = vk;
      w.x[at] = std::clamp(w.x[at] + vk, obj.lower[k], obj.upper[k]);
    }
  }
}

// Re-initialises a random half of the particles, never the one holding Gbest.
void reinitialise_half(const BatchObjective& obj, Swarm& w) {
  const long np = w.np;
  std::vector<long> order(static_cast<size_t>(np));
  std::iota(order.begin(), order.end(), 0L);
  for (long i = np - 1; i > 0; --i)
    std::swap(order[i], order[static_cast<size_t>(w.rng.below(static_cast<uint64_t>(i + 1)))]);
  long done = 0;
  for (long i : order) {
    if (done == np / 2) break;
    if (i == w.gbest_owner) continue;
    init_particle(obj, w, i);
    ++done;
  }
}

}  // namespace

RunRecord minimise_pso(const BatchObjective& obj, const PsoSettings& s, const StopRule& stop,
                       uint64_t seed, const ProgressFn& progress) {
  check_settings(s, stop);
  RunRecord rec;
  RunLog log(stop, progress, rec);
  Swarm w(obj, s.population, seed);
  for (long i = 0; i < w.np; ++i) init_particle(obj, w, i);

  int stall = 0;
  while (!log.done()) {
    const long m = std::min(w.np, log.remaining());
    obj.evaluate(w.x.data(), w.np, m, w.fx.data());
    log.count(m);
    const bool improved = update_bests(w, m);
    log.offer(w.fg, [&](std::vector<double>& out) { out = w.gbest; });
    log.end_generation();
    if (m < w.np || log.done()) break;

    stall = improved ? 0 : stall + 1;
    const double inertia = s.w_start + (s.w_end - s.w_start) * static_cast<double>(rec.evaluations) /
                                           static_cast<double>(stop.budget);
    move_swarm(obj, s, inertia, w);
    if (stall >= s.stall_generations) {
      reinitialise_half(obj, w);
      stall = 0;
    }
  }
  return rec;
}

}  // namespace gpm::calib::global
