#include "calib/global/decision_space.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "models/errors.hpp"

namespace gpm::calib::global {

Box default_box(const Geometry& nominal, const FreeMask& free) {
  Box box;
  for (int i = 0; i < kNumParams; ++i) {
    const double half = !free[static_cast<size_t>(i)] ? 0.0 : is_offset(i) ? 0.2 : 5.0;
    box.lower[static_cast<size_t>(i)] = nominal[i] - half;
    box.upper[static_cast<size_t>(i)] = nominal[i] + half;
  }
  return box;
}

namespace {

// Range of l_ac = la cos dth and l_as = la sin dth over the polar sector
// [la_lo, la_hi] x [th_lo, th_hi] (th range within (-pi/2, pi/2)).
struct SectorBox {
  double ac_lo, ac_hi, as_lo, as_hi;
};

SectorBox sector_box(double la_lo, double la_hi, double th_lo, double th_hi) {
  const double cmin = std::min(std::cos(th_lo), std::cos(th_hi));
  const double cmax = (th_lo <= 0.0 && th_hi >= 0.0) ? 1.0 : std::max(std::cos(th_lo), std::cos(th_hi));
  const double slo = std::sin(th_lo), shi = std::sin(th_hi);
  return {la_lo * cmin, la_hi * cmax, (slo < 0 ? la_hi : la_lo) * slo,
          (shi > 0 ? la_hi : la_lo) * shi};
}

}  // namespace

DecisionSpace::DecisionSpace(const Problem& problem, Cost cost, const Box& box)
    : cost_(cost), fixed_(problem.start) {
  if (cost != Cost::kJ1 && cost != Cost::kJ2 && cost != Cost::kJ3)
    throw InputError(fmt::format("global solvers: cost {} is not supported (use j1, j2 or j3)",
                                 cost_name(cost)));
  const auto is_free = [&](int p) { return problem.free[static_cast<size_t>(p)]; };
  for (int p = 0; p < kNumParams; ++p) {
    if (!is_free(p)) continue;
    const double lo = box.lower[static_cast<size_t>(p)], hi = box.upper[static_cast<size_t>(p)];
    if (!(lo < hi) || !std::isfinite(lo) || !std::isfinite(hi))
      throw InputError(fmt::format("search box of {}: need finite lower < upper, got [{}, {}]",
                                   param_name(p), lo, hi));
    if (is_offset(p) && !(lo > -std::numbers::pi / 2 && hi < std::numbers::pi / 2))
      throw InputError(fmt::format("search box of {}: offsets must lie within (-pi/2, pi/2)",
                                   param_name(p)));
    if (is_length(p) && !(lo > 0.0))
      throw InputError(fmt::format("search box of {}: lengths must stay positive", param_name(p)));
  }
  for (int i = 0; i < 3; ++i)
    decoupled_[static_cast<size_t>(i)] = cost == Cost::kJ3 && is_free(la(i)) && is_free(dth(i));
  for (int p = 0; p < kNumParams; ++p) {
    if (!is_free(p)) continue;
    const bool la_p = p >= kLa1 && p <= kLa3, dth_p = p >= kDth1 && p <= kDth3;
    const int chain = la_p ? p - kLa1 : dth_p ? p - kDth1 : -1;
    if (chain >= 0 && decoupled_[static_cast<size_t>(chain)]) {
      const auto sb = sector_box(box.lower[la(chain)], box.upper[la(chain)],
                                 box.lower[dth(chain)], box.upper[dth(chain)]);
      if (la_p) {
        coords_.push_back({Kind::kLac, chain});
        names_.push_back(fmt::format("lac{}", chain + 1));
        lower_.push_back(sb.ac_lo);
        upper_.push_back(sb.ac_hi);
      } else {
        coords_.push_back({Kind::kLas, chain});
        names_.push_back(fmt::format("las{}", chain + 1));
        lower_.push_back(sb.as_lo);
        upper_.push_back(sb.as_hi);
      }
      continue;
    }
    coords_.push_back({Kind::kParam, p});
    names_.emplace_back(param_name(p));
    lower_.push_back(box.lower[static_cast<size_t>(p)]);
    upper_.push_back(box.upper[static_cast<size_t>(p)]);
  }
  if (coords_.empty()) throw InputError("global solvers: no parameter is free");

  // Copy plan of to_kernel.
  auto source_of = [&](Kind kind, int index) {
    for (size_t k = 0; k < coords_.size(); ++k)
      if (coords_[k].kind == kind && coords_[k].index == index) return static_cast<int>(k);
    return -1;
  };
  for (int i = 0; i < 3; ++i) {
    const auto set = [&](int v, int src, double value) {
      kv_src_[static_cast<size_t>(v)] = src;
      kv_const_[static_cast<size_t>(v)] = value;
    };
    set(kKxa1 + 2 * i, source_of(Kind::kParam, xa(i)), fixed_[xa(i)]);
    set(kKya1 + 2 * i, source_of(Kind::kParam, ya(i)), fixed_[ya(i)]);
    set(kKlb1 + i, source_of(Kind::kParam, lb(i)), fixed_[lb(i)]);
    const double l = fixed_[la(i)], th = fixed_[dth(i)];
    if (decoupled_[static_cast<size_t>(i)]) {
      set(kKlac1 + i, source_of(Kind::kLac, i), 0.0);
      set(kKlas1 + i, source_of(Kind::kLas, i), 0.0);
    } else {
      set(kKlac1 + i, -1, l * std::cos(th));
      set(kKlas1 + i, -1, l * std::sin(th));
      const int la_src = source_of(Kind::kParam, la(i)), dth_src = source_of(Kind::kParam, dth(i));
      if (la_src >= 0 || dth_src >= 0) trig_.push_back({i, la_src, dth_src});
    }
  }
}

void DecisionSpace::to_kernel(const double* x, long stride, long count, double* kv) const {
  constexpr int B = kKernelBlock;
  for (int v = 0; v < kNumKernelVars; ++v) {
    double* out = kv + v * B;
    const int k = kv_src_[static_cast<size_t>(v)];
    if (k < 0) {
      std::fill_n(out, B, kv_const_[static_cast<size_t>(v)]);
    } else {
      const double* in = x + k * stride;
      for (int c = 0; c < B; ++c) out[c] = in[c < count ? c : 0];
    }
  }
  for (const auto& t : trig_) {
    for (int c = 0; c < B; ++c) {
      const long src = c < count ? c : 0;
      const double l = t.la_src < 0 ? fixed_[la(t.chain)] : x[t.la_src * stride + src];
      const double th = t.dth_src < 0 ? fixed_[dth(t.chain)] : x[t.dth_src * stride + src];
      kv[(kKlac1 + t.chain) * B + c] = l * std::cos(th);
      kv[(kKlas1 + t.chain) * B + c] = l * std::sin(th);
    }
  }
}

void DecisionSpace::to_kernel_one(const double* d, double* kv) const {
  for (int v = 0; v < kNumKernelVars; ++v) {
    const int k = kv_src_[static_cast<size_t>(v)];
    kv[v] = k < 0 ? kv_const_[static_cast<size_t>(v)] : d[k];
  }
  for (const auto& t : trig_) {
    const double l = t.la_src < 0 ? fixed_[la(t.chain)] : d[t.la_src];
    const double th = t.dth_src < 0 ? fixed_[dth(t.chain)] : d[t.dth_src];
    kv[kKlac1 + t.chain] = l * std::cos(th);
    kv[kKlas1 + t.chain] = l * std::sin(th);
  }
}

Geometry DecisionSpace::to_geometry(const std::vector<double>& d) const {
  Geometry g = fixed_;
  std::array<double, 3> lac{}, las{};
  for (size_t k = 0; k < coords_.size(); ++k) {
    switch (coords_[k].kind) {
      case Kind::kParam: g[coords_[k].index] = d[k]; break;
      case Kind::kLac: lac[static_cast<size_t>(coords_[k].index)] = d[k]; break;
      case Kind::kLas: las[static_cast<size_t>(coords_[k].index)] = d[k]; break;
    }
  }
  for (int i = 0; i < 3; ++i) {
    if (!decoupled_[static_cast<size_t>(i)]) continue;
    g[la(i)] = std::hypot(lac[static_cast<size_t>(i)], las[static_cast<size_t>(i)]);  // eq. 44
    g[dth(i)] = std::atan2(las[static_cast<size_t>(i)], lac[static_cast<size_t>(i)]);
  }
  return g;
}

std::vector<double> DecisionSpace::from_geometry(const Geometry& g) const {
  std::vector<double> d;
  for (const auto& c : coords_) {
    switch (c.kind) {
      case Kind::kParam: d.push_back(g[c.index]); break;
      case Kind::kLac: d.push_back(g[la(c.index)] * std::cos(g[dth(c.index)])); break;
      case Kind::kLas: d.push_back(g[la(c.index)] * std::sin(g[dth(c.index)])); break;
    }
  }
  return d;
}

}  // namespace gpm::calib::global
