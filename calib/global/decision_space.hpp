// The decision vector the global optimisers search, and how it maps to the
// 15 geometric parameters for each error function.
//
// J1 and J2 (eq. 37, 39): one decision coordinate per free parameter, in the
// order xa1 ... dth3 of docs/FORMATS.md, with that parameter's box.
// J3 (eq. 43): the same, except that a chain whose la_i and dth_i are both
// free is searched in the decoupled variables l_ac_i = la_i cos dth_i and
// l_as_i = la_i sin dth_i (eq. 41), which take the places of la_i and dth_i.
// Their box is the smallest box holding the image of [la_min, la_max] x
// [dth_min, dth_max] (a polar sector), so every (la, dth) of the paper's box
// can be reached; a point of the corner regions outside the sector maps back
// (eq. 44 per docs/EQUATIONS.md: la = hypot(l_ac, l_as), dth = atan2(l_as, l_ac)) to
// values slightly outside the paper's box. A chain with only one of la_i,
// dth_i free keeps the coupled variable (J3 then equals J2 for that chain).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "calib/global/closure_kernel.hpp"
#include "calib/problem.hpp"

namespace gpm::calib::global {

// Default search box: paper Table 5 generalised to any nominal geometry:
// nominal +- 5 mm for base coordinates and link lengths, nominal +- 0.2 rad
// for encoder offsets; fixed parameters get a zero-width box at nominal.
Box default_box(const Geometry& nominal, const FreeMask& free);

class DecisionSpace {
 public:
  // The space for problem (fixed values from problem.start), cost and box.
  // Throws InputError when a free parameter's box is empty or inverted, no
  // parameter is free, or cost is not j1, j2 or j3.
  DecisionSpace(const Problem& problem, Cost cost, const Box& box);

  int dim() const { return static_cast<int>(names_.size()); }
  const std::vector<std::string>& names() const { return names_; }
  const std::vector<double>& lower() const { return lower_; }
  const std::vector<double>& upper() const { return upper_; }
  Cost cost() const { return cost_; }
  // True when chain i is searched in l_ac_i, l_as_i.
  bool decoupled(int chain) const { return decoupled_[static_cast<size_t>(chain)]; }

  // Kernel variables (closure_kernel.hpp) of up to kKernelBlock candidates
  // x[k * stride + c], c < count; the block is padded with candidate 0.
  void to_kernel(const double* x, long stride, long count, double* kv) const;

  // Kernel variables kv[v] of the single decision vector d.
  void to_kernel_one(const double* d, double* kv) const;

  // The 15 parameters of decision vector d (eq. 44 per docs/EQUATIONS.md for decoupled chains).
  Geometry to_geometry(const std::vector<double>& d) const;

  // The decision vector of geometry g (inverse of to_geometry on free parameters).
  std::vector<double> from_geometry(const Geometry& g) const;

 private:
  // What decision coordinate k stands for.
  enum class Kind { kParam, kLac, kLas };
  struct Coord {
    Kind kind;
    int index;  // parameter index (kParam) or chain (kLac, kLas)
  };
  Cost cost_;
  Geometry fixed_;
  std::vector<Coord> coords_;
  std::vector<std::string> names_;
  std::vector<double> lower_, upper_;
  std::array<bool, 3> decoupled_{};
  // Precomputed copy plan of to_kernel: kernel variable v comes from decision
  // coordinate kv_src_[v], or is the constant kv_const_[v] when that is -1.
  std::array<int, kNumKernelVars> kv_src_{};
  std::array<double, kNumKernelVars> kv_const_{};
  // Chains whose l_ac, l_as come from coupled (la, dth): source coordinate or
  // -1 for a fixed value.
  struct TrigChain {
    int chain, la_src, dth_src;
  };
  std::vector<TrigChain> trig_;
};

}  // namespace gpm::calib::global
