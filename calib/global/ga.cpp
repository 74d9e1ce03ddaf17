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

}  // namespace

RunRecord minimise_ga(const BatchObjective& obj, const GaSettings& s, const StopRule& stop,
                      uint64_t seed, const ProgressFn& progress) {
  const int n = obj.dim();
  const long np = s.population;
  if (np < 2) throw InputError("GA: the population must have at least 2 individuals");
  if (s.tournament < 1) throw InputError("GA: the tournament needs at least 1 individual");
  if (stop.budget < 1) throw InputError("GA: the budget must be at least 1 evaluation");
  RunRecord rec;
  RunLog log(stop, progress, rec);
  Rng rng(seed);

  Layout lay;
  for (int k = 0; k < n; ++k) {
    lay.offset.push_back(lay.total);
    lay.bits.push_back(ga_bits(obj.upper[k] - obj.lower[k], s.precision));
    lay.total += lay.bits.back();
  }

  // genes[i * n + k]: the integer of parameter k of individual i.
  std::vector<uint64_t> genes(static_cast<size_t>(np * n)), next(genes.size());
  std::vector<double> fit(static_cast<size_t>(np)), next_fit(fit.size());
  std::vector<char> dirty(static_cast<size_t>(np), 1), next_dirty(dirty.size());
  std::vector<double> x(static_cast<size_t>(n * np)), fx(static_cast<size_t>(np));
  std::vector<long> todo;

  auto random_gene = [&](int k) { return rng.bits() & low_mask(lay.bits[k]); };
  auto decode = [&](uint64_t g, int k) {
    const double scale = static_cast<double>(low_mask(lay.bits[k]));
    const double v = obj.lower[k] + static_cast<double>(g) * (obj.upper[k] - obj.lower[k]) / scale;
    return std::min(v, obj.upper[k]);
  };
  auto flip_bit = [&](long i, int b) {
    const int k = static_cast<int>(std::upper_bound(lay.offset.begin(), lay.offset.end(), b) -
                                   lay.offset.begin()) - 1;
    genes[i * n + k] ^= 1ULL << (b - lay.offset[k]);
  };
  // Single-point crossover of individuals a and b: bits at positions >= cut swap.
  auto cross = [&](long a, long b, int cut) {
    for (int k = 0; k < n; ++k) {
      const int lo = lay.offset[k], hi = lo + lay.bits[k];
      if (hi <= cut) continue;
      const uint64_t mask = low_mask(lay.bits[k]) & ~low_mask(std::max(0, cut - lo));
      uint64_t& ga = genes[a * n + k];
      uint64_t& gb = genes[b * n + k];
      const uint64_t diff = (ga ^ gb) & mask;
      ga ^= diff;
      gb ^= diff;
    }
  };
  // Evaluates the dirty individuals (as many as the budget allows).
  auto evaluate_dirty = [&]() {
    todo.clear();
    for (long i = 0; i < np; ++i)
      if (dirty[i]) todo.push_back(i);
    const long m = std::min(static_cast<long>(todo.size()), log.remaining());
    for (long c = 0; c < m; ++c)
      for (int k = 0; k < n; ++k) x[k * np + c] = decode(genes[todo[c] * n + k], k);
    obj.evaluate(x.data(), np, m, fx.data());
    log.count(m);
    bool improved = false;
    for (long c = 0; c < m; ++c) {
      const long i = todo[c];
      fit[i] = fx[c];
      dirty[i] = 0;
      improved |= log.offer(fx[c], [&](std::vector<double>& out) {
        out.resize(static_cast<size_t>(n));
        for (int k = 0; k < n; ++k) out[k] = x[k * np + c];
      });
    }
    return std::pair<bool, bool>{improved, m == static_cast<long>(todo.size())};
  };

  for (long i = 0; i < np; ++i)
    for (int k = 0; k < n; ++k) genes[i * n + k] = random_gene(k);
  auto [first_improved, complete] = evaluate_dirty();
  (void)first_improved;
  log.end_generation();
  int stall = 0;

  while (complete && !log.done()) {
    const long best = std::min_element(fit.begin(), fit.end()) - fit.begin();
    // Reproduction: the best kept in slot 0, tournaments fill the rest.
    std::copy_n(&genes[best * n], n, &next[0]);
    next_fit[0] = fit[best];
    next_dirty[0] = 0;
    for (long i = 1; i < np; ++i) {
      long win = static_cast<long>(rng.below(static_cast<uint64_t>(np)));
      for (int t = 1; t < s.tournament; ++t) {
        const long c = static_cast<long>(rng.below(static_cast<uint64_t>(np)));
        if (fit[c] < fit[win]) win = c;
      }
      std::copy_n(&genes[win * n], n, &next[i * n]);
      next_fit[i] = fit[win];
      next_dirty[i] = 0;
    }
    genes.swap(next);
    fit.swap(next_fit);
    dirty.swap(next_dirty);
    // Crossover of consecutive pairs among slots 1..N-1.
    for (long a = 1; a + 1 < np; a += 2) {
      if (rng.uniform() < s.p_crossover && lay.total > 1) {
        const int cut = 1 + static_cast<int>(rng.below(static_cast<uint64_t>(lay.total - 1)));
        cross(a, a + 1, cut);
        dirty[a] = dirty[a + 1] = 1;
      }
    }
    // Two-bit mutation.
    for (long i = 1; i < np; ++i) {
      if (rng.uniform() < s.p_mutation) {
        flip_bit(i, static_cast<int>(rng.below(static_cast<uint64_t>(lay.total))));
        flip_bit(i, static_cast<int>(rng.below(static_cast<uint64_t>(lay.total))));
        dirty[i] = 1;
      }
    }
    if (stall >= s.stall_generations) {
      std::vector<long> order(static_cast<size_t>(np - 1));
      std::iota(order.begin(), order.end(), 1L);
      for (long i = static_cast<long>(order.size()) - 1; i > 0; --i)
        std::swap(order[i], order[static_cast<size_t>(rng.below(static_cast<uint64_t>(i + 1)))]);
      for (long j = 0; j < np / 2; ++j) {
        const long i = order[static_cast<size_t>(j)];
        for (int k = 0; k < n; ++k) genes[i * n + k] = random_gene(k);
        dirty[i] = 1;
      }
      stall = 0;
    }
    const auto [improved, all] = evaluate_dirty();
    complete = all;
    stall = improved ? 0 : stall + 1;
    log.end_generation();
  }
  return rec;
}

}  // namespace gpm::calib::global
