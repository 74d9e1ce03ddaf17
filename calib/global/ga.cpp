#include "calib/global/ga.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

#include "models/rng.hpp"
#include "calib/global/run_log.hpp"
#include "models/errors.hpp"

namespace gpm::calib::global {

int ga_bits(double width, double precision) {
  if (!(width > precision)) return 1;
  return std::clamp(static_cast<int>(std::ceil(std::log2(width / precision))), 1, 52);
}

namespace {

// The binary layout: parameter k occupies bits [offset[k], offset[k] + bits[k]).
struct Layout {
  std::vector<int> bits, offset;
  int total = 0;
};

uint64_t low_mask(int nbits) { return nbits >= 64 ? ~0ULL : (1ULL << nbits) - 1; }

// Throws InputError for a population, tournament or budget GA cannot run with.
void check_settings(const GaSettings& s, const StopRule& stop) {
  if (s.population < 2) throw InputError("GA: the population must have at least 2 individuals");
  if (s.tournament < 1) throw InputError("GA: the tournament needs at least 1 individual");
  if (stop.budget < 1) throw InputError("GA: the budget must be at least 1 evaluation");
}

// The layout of obj's parameters at the given precision (ga_bits each).
Layout layout_of(const BatchObjective& obj, double precision) {
  Layout lay;
  for (int k = 0; k < obj.dim(); ++k) {
    lay.offset.push_back(lay.total);
    lay.bits.push_back(ga_bits(obj.upper[k] - obj.lower[k], precision));
    lay.total += lay.bits.back();
  }
  return lay;
}

// The population: genes[i * n + k], the integer of parameter k of individual
// i, with its fitness and whether it needs evaluating (dirty), the next
// generation's buffers, and the evaluation batch (x parameter-major).
struct Population {
  Population(const BatchObjective& obj, const GaSettings& s)
      : n(obj.dim()), np(s.population), lay(layout_of(obj, s.precision)),
        genes(static_cast<size_t>(np * n)), next(genes.size()), fit(static_cast<size_t>(np)),
        next_fit(fit.size()), dirty(static_cast<size_t>(np), 1), next_dirty(dirty.size()),
        x(static_cast<size_t>(n * np)), fx(static_cast<size_t>(np)) {}
  const int n;
  const long np;
  const Layout lay;
  std::vector<uint64_t> genes, next;
  std::vector<double> fit, next_fit;
  std::vector<char> dirty, next_dirty;
  std::vector<double> x, fx;
  std::vector<long> todo;
};

// A random integer of parameter k's width.
uint64_t random_gene(const Layout& lay, int k, Rng& rng) { return rng.bits() & low_mask(lay.bits[k]); }

// Parameter k's value of integer g: the box spread over the integer's range.
double decode(const BatchObjective& obj, const Layout& lay, uint64_t g, int k) {
  const double scale = static_cast<double>(low_mask(lay.bits[k]));
  const double v = obj.lower[k] + static_cast<double>(g) * (obj.upper[k] - obj.lower[k]) / scale;
  return std::min(v, obj.upper[k]);
}

// Flips bit b of individual i's chromosome.
void flip_bit(Population& pop, long i, int b) {
  const Layout& lay = pop.lay;
  const int k = static_cast<int>(std::upper_bound(lay.offset.begin(), lay.offset.end(), b) -
                                 lay.offset.begin()) - 1;
  pop.genes[i * pop.n + k] ^= 1ULL << (b - lay.offset[k]);
}

// Single-point crossover of individuals a and b: bits at positions >= cut swap.
void cross(Population& pop, long a, long b, int cut) {
  for (int k = 0; k < pop.n; ++k) {
    const int lo = pop.lay.offset[k], hi = lo + pop.lay.bits[k];
    if (hi <= cut) continue;
    const uint64_t mask = low_mask(pop.lay.bits[k]) & ~low_mask(std::max(0, cut - lo));
    uint64_t& ga = pop.genes[a * pop.n + k];
    uint64_t& gb = pop.genes[b * pop.n + k];
    const uint64_t diff = (ga ^ gb) & mask;
    ga ^= diff;
    gb ^= diff;
  }
}

// Evaluates the dirty individuals (as many as the budget allows); returns
// whether the best improved and whether all of them were evaluated.
std::pair<bool, bool> evaluate_dirty(const BatchObjective& obj, RunLog& log, Population& pop) {
  const int n = pop.n;
  const long np = pop.np;
  pop.todo.clear();
  for (long i = 0; i < np; ++i)
    if (pop.dirty[i]) pop.todo.push_back(i);
  const long m = std::min(static_cast<long>(pop.todo.size()), log.remaining());
  for (long c = 0; c < m; ++c)
    for (int k = 0; k < n; ++k) pop.x[k * np + c] = decode(obj, pop.lay, pop.genes[pop.todo[c] * n + k], k);
  obj.evaluate(pop.x.data(), np, m, pop.fx.data());
  log.count(m);
  bool improved = false;
  for (long c = 0; c < m; ++c) {
    const long i = pop.todo[c];
    pop.fit[i] = pop.fx[c];
    pop.dirty[i] = 0;
    improved |= log.offer(pop.fx[c], [&](std::vector<double>& out) {
      out.resize(static_cast<size_t>(n));
      for (int k = 0; k < n; ++k) out[k] = pop.x[k * np + c];
    });
  }
  return std::pair<bool, bool>{improved, m == static_cast<long>(pop.todo.size())};
}

// Reproduction: the best kept in slot 0, tournaments fill the rest.
void reproduce(const GaSettings& s, Rng& rng, Population& pop) {
  const int n = pop.n;
  const long np = pop.np;
  const long best = std::min_element(pop.fit.begin(), pop.fit.end()) - pop.fit.begin();
  std::copy_n(&pop.genes[best * n], n, &pop.next[0]);
  pop.next_fit[0] = pop.fit[best];
  pop.next_dirty[0] = 0;
  for (long i = 1; i < np; ++i) {
    long win = static_cast<long>(rng.below(static_cast<uint64_t>(np)));
    for (int t = 1; t < s.tournament; ++t) {
      const long c = static_cast<long>(rng.below(static_cast<uint64_t>(np)));
      if (pop.fit[c] < pop.fit[win]) win = c;
    }
    std::copy_n(&pop.genes[win * n], n, &pop.next[i * n]);
    pop.next_fit[i] = pop.fit[win];
    pop.next_dirty[i] = 0;
  }
  pop.genes.swap(pop.next);
  pop.fit.swap(pop.next_fit);
  pop.dirty.swap(pop.next_dirty);
}

// Crossover of consecutive pairs among slots 1..N-1, then two-bit mutation.
void cross_and_mutate(const GaSettings& s, Rng& rng, Population& pop) {
  const int total = pop.lay.total;
  for (long a = 1; a + 1 < pop.np; a += 2) {
    if (rng.uniform() < s.p_crossover && total > 1) {
      const int cut = 1 + static_cast<int>(rng.below(static_cast<uint64_t>(total - 1)));
      cross(pop, a, a + 1, cut);
      pop.dirty[a] = pop.dirty[a + 1] = 1;
    }
  }
  for (long i = 1; i < pop.np; ++i) {
    if (rng.uniform() < s.p_mutation) {
      flip_bit(pop, i, static_cast<int>(rng.below(static_cast<uint64_t>(total))));
      flip_bit(pop, i, static_cast<int>(rng.below(static_cast<uint64_t>(total))));
      pop.dirty[i] = 1;
    }
  }
}

// New random chromosomes for a random half of slots 1..N-1 (the best in slot 0 stays).
void restart_half(Rng& rng, Population& pop) {
  std::vector<long> order(static_cast<size_t>(pop.np - 1));
  std::iota(order.begin(), order.end(), 1L);
  for (long i = static_cast<long>(order.size()) - 1; i > 0; --i)
    std::swap(order[i], order[static_cast<size_t>(rng.below(static_cast<uint64_t>(i + 1)))]);
  for (long j = 0; j < pop.np / 2; ++j) {
    const long i = order[static_cast<size_t>(j)];
    for (int k = 0; k < pop.n; ++k) pop.genes[i * pop.n + k] = random_gene(pop.lay, k, rng);
    pop.dirty[i] = 1;
  }
}

}  // namespace

RunRecord minimise_ga(const BatchObjective& obj, const GaSettings& s, const StopRule& stop,
                      uint64_t seed, const ProgressFn& progress) {
  check_settings(s, stop);
  Rng rng(seed);
  Population pop(obj, s);
  RunRecord rec;
  RunLog log(stop, progress, rec);
  for (long i = 0; i < pop.np; ++i)
    for (int k = 0; k < pop.n; ++k) pop.genes[i * pop.n + k] = random_gene(pop.lay, k, rng);
  bool complete = evaluate_dirty(obj, log, pop).second;
  log.end_generation();
  int stall = 0;
  while (complete && !log.done()) {
    reproduce(s, rng, pop);
    cross_and_mutate(s, rng, pop);
    if (stall >= s.stall_generations) {
      restart_half(rng, pop);
      stall = 0;
    }
    const auto [improved, all] = evaluate_dirty(obj, log, pop);
    complete = all;
    stall = improved ? 0 : stall + 1;
    log.end_generation();
  }
  return rec;
}

}  // namespace gpm::calib::global
