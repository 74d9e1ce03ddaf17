// Excitation design (excitation.hpp: the criteria). Algorithm:
//  1. candidates: the reachable grid with margins (candidates.hpp);
//  2. greedy start (Wynn / sequential D-optimal): starting from a small ridge
//     M = delta I, add the candidate maximising g' M^-1 g, since
//     det(M + g g') = det(M) (1 + g' M^-1 g);
//  3. exchange (Fedorov): swap a chosen pose i for a candidate j while the
//     criterion improves. For D the determinant ratio of a swap is
//       det(M - g_i g_i' + g_j g_j') / det M = (1 + d_j)(1 - d_i) + d_ij^2,
//     d_i = g_i' M^-1 g_i, d_ij = g_i' M^-1 g_j; the best pair is swapped
//     until no ratio exceeds 1. For worst, the new variances of every swap
//     follow from two Sherman-Morrison rank-one updates in O(p):
//       add j:    C1 = C - u_j u_j' / (1 + d_j),             u_j = C g_j
//       remove i: C2 = C1 + v v' / (1 - g_i' C1 g_i),        v = C1 g_i
//     so diag(C2) = diag(C) - u_j.^2 / (1 + d_j) + v.^2 / (1 - d_i + d_ij^2 / (1 + d_j)),
//     v = u_i - u_j d_ij / (1 + d_j). The max is not smooth (ties stall a
//     steepest exchange), so the exchange first minimises the smooth
//     surrogates sum_k (s_k^2 C_kk)^q for q = 1 (A-optimal), 4, 16, then the
//     exact max.
//  The result is the best design seen on the chosen criterion, so it is never
//  worse than the greedy start.
#include "calib/excitation/excitation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Cholesky>
#include <fmt/format.h>

#include "models/bounds.hpp"
#include "models/errors.hpp"

namespace gpm::calib::excitation {
namespace {

// Information matrix sum_{j in chosen} g_j g_j' (unit noise).
Eigen::MatrixXd information_of(const Eigen::MatrixXd& rows, const std::vector<int>& chosen) {
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(rows.cols(), rows.cols());
  for (int j : chosen) M.selfadjointView<Eigen::Lower>().rankUpdate(rows.row(j).transpose());
  return M.selfadjointView<Eigen::Lower>();
}

// M^-1 by Cholesky; nullopt when M is not positive definite.
std::optional<Eigen::MatrixXd> inverse_spd(const Eigen::MatrixXd& M) {
  const Eigen::LLT<Eigen::MatrixXd> llt(M);
  if (llt.info() != Eigen::Success) return std::nullopt;
  const Eigen::MatrixXd C = llt.solve(Eigen::MatrixXd::Identity(M.rows(), M.cols()));
  if (!C.allFinite() || (C.diagonal().array() <= 0.0).any()) return std::nullopt;
  return C;
}

std::vector<char> membership(Eigen::Index n, const std::vector<int>& chosen) {
  std::vector<char> in(static_cast<size_t>(n), 0);
  for (int j : chosen) in[static_cast<size_t>(j)] = 1;
  return in;
}

// x^q for q a power of two (1, 4 or 16) by repeated squaring.
double power_of_two(double x, int q) {
  for (int e = 1; e < q; e *= 2) x *= x;
  return x;
}

// Objective of scaled variances v: max (q = 0) or sum (v / ref)^q.
double variance_objective(const Eigen::ArrayXd& v, int q, double ref) {
  if (q == 0) return v.maxCoeff();
  double sum = 0.0;
  for (Eigen::Index k = 0; k < v.size(); ++k) sum += power_of_two(v[k] / ref, q);
  return sum;
}

// The positioning criterion's exchange from chosen (the worst design) over
// the candidates cand; sets bound_um to its value; returns the swaps.
int positioning_stage(const Robot& nominal, const DesignOptions& o, const std::vector<Eigen::Vector2d>& cand,
                      std::vector<int>& chosen, double& bound_um) {
  const Eigen::MatrixXd rows = rows_with_cyclic_error(nominal, o.free, cand);
  const PositioningCriterion c = positioning_criterion(nominal, o.free, o.positioning, o.sigma, rows);
  const int swaps = exchange_positioning(rows, chosen, c, o.max_exchanges);
  bound_um = positioning_bound_um(rows, chosen, c);
  return swaps;
}

}  // namespace

std::optional<Criterion> parse_criterion(std::string_view name) {
  if (name == "d") return Criterion::kDOptimal;
  if (name == "worst") return Criterion::kWorst;
  if (name == "positioning") return Criterion::kPositioning;
  return std::nullopt;
}

std::string_view criterion_name(Criterion c) {
  return c == Criterion::kDOptimal ? "d" : c == Criterion::kWorst ? "worst" : "positioning";
}

int design_stages(Criterion c) { return c == Criterion::kDOptimal ? 2 : c == Criterion::kWorst ? 6 : 7; }

double criterion_value(Criterion c, const Bounds& b) {
  return c == Criterion::kDOptimal ? -b.log_det : b.worst_mm;
}

std::vector<int> greedy_d_optimal(const Eigen::MatrixXd& rows, int count, double delta) {
  const Eigen::Index n = rows.rows(), p = rows.cols();
  if (count > n) throw InputError(fmt::format("cannot choose {} poses from {} candidates", count, n));
  const double mean_sq = rows.squaredNorm() / static_cast<double>(std::max<Eigen::Index>(n, 1));
  Eigen::MatrixXd Minv = Eigen::MatrixXd::Identity(p, p) / (delta * mean_sq);
  std::vector<char> used(static_cast<size_t>(n), 0);
  std::vector<int> chosen;
  for (int t = 0; t < count; ++t) {
    // Gain of each candidate: det(M + g g') / det(M) = 1 + g' M^-1 g.
    const Eigen::VectorXd d = (rows * Minv).cwiseProduct(rows).rowwise().sum();
    int best = -1;
    for (Eigen::Index j = 0; j < n; ++j)
      if (!used[static_cast<size_t>(j)] && (best < 0 || d[j] > d[best])) best = static_cast<int>(j);
    used[static_cast<size_t>(best)] = 1;
    chosen.push_back(best);
    // Sherman-Morrison: (M + g g')^-1 = M^-1 - M^-1 g g' M^-1 / (1 + g' M^-1 g).
    const Eigen::VectorXd u = Minv * rows.row(best).transpose();
    Minv -= u * u.transpose() / (1.0 + d[best]);
  }
  return chosen;
}

int exchange_d_optimal(const Eigen::MatrixXd& rows, std::vector<int>& chosen, int max_swaps) {
  const Eigen::Index n = rows.rows();
  int swaps = 0;
  while (swaps < max_swaps) {
    const auto Minv = inverse_spd(information_of(rows, chosen));
    if (!Minv) break;
    const Eigen::MatrixXd U = rows * *Minv;                          // row j: (M^-1 g_j)'
    const Eigen::VectorXd d = U.cwiseProduct(rows).rowwise().sum();  // d_j = g_j' M^-1 g_j
    const std::vector<char> in = membership(n, chosen);
    double best_ratio = 1.0 + 1e-10;
    int best_slot = -1, best_j = -1;
    for (size_t a = 0; a < chosen.size(); ++a) {
      const int i = chosen[a];
      const Eigen::VectorXd dij = rows * U.row(i).transpose();  // g_j' M^-1 g_i
      for (Eigen::Index j = 0; j < n; ++j) {
        if (in[static_cast<size_t>(j)]) continue;
        // det ratio of swapping i out and j in.
        const double ratio = (1.0 + d[j]) * (1.0 - d[i]) + dij[j] * dij[j];
        if (ratio > best_ratio) best_ratio = ratio, best_slot = static_cast<int>(a), best_j = static_cast<int>(j);
      }
    }
    if (best_slot < 0) break;
    chosen[static_cast<size_t>(best_slot)] = best_j;
    ++swaps;
  }
  return swaps;
}

namespace {

// The objective (variance_objective) of swapping chosen pose i out and each
// candidate j in, for every j at once (+inf where a variance would not be
// positive or the swap is singular). U = rows C, d_j = g_j' C g_j, a = 1 + d,
// after_add: diag(C1) of adding j alone (a row per j).
Eigen::ArrayXd swap_objectives(const Eigen::MatrixXd& rows, const Eigen::MatrixXd& U, const Eigen::ArrayXd& d,
                               const Eigen::ArrayXd& a, const Eigen::ArrayXXd& after_add, int i, int q, double ref) {
  const Eigen::Index n = rows.rows();
  const Eigen::ArrayXd dij = (rows * U.row(i).transpose()).array();  // g_j' C g_i
  const Eigen::ArrayXd e = d[i] - dij.square() / a;                   // g_i' C1 g_i
  const Eigen::ArrayXd w = dij / a;
  Eigen::ArrayXd obj = Eigen::ArrayXd::Zero(n), diag(n);
  Eigen::Array<bool, Eigen::Dynamic, 1> ok = (1.0 - e) > 1e-9;
  for (Eigen::Index k = 0; k < U.cols(); ++k) {
    // v = C1 g_i = u_i - u_j d_ij / (1 + d_j); diag(C2) = diag(C1) + v.^2 / (1 - e).
    diag = after_add.col(k) + (U(i, k) - U.col(k).array() * w).square() / (1.0 - e);
    ok = ok && diag > 0.0;
    if (q == 0) {
      obj = obj.max(diag);
    } else {
      Eigen::ArrayXd x = diag / ref;
      for (int p = 1; p < q; p *= 2) x = x.square();
      obj += x;
    }
  }
  return ok.select(obj, std::numeric_limits<double>::infinity());
}

}  // namespace

int exchange_variances(const Eigen::MatrixXd& rows, std::vector<int>& chosen, int q, int max_swaps) {
  const Eigen::Index n = rows.rows();
  int swaps = 0;
  while (swaps < max_swaps) {
    const auto C = inverse_spd(information_of(rows, chosen));
    if (!C) break;
    const Eigen::ArrayXd c_diag = C->diagonal().array();
    const double ref = c_diag.maxCoeff();
    const double current = variance_objective(c_diag, q, ref);
    const Eigen::MatrixXd U = rows * *C;                             // row j: u_j' = (C g_j)'
    const Eigen::ArrayXd d = U.cwiseProduct(rows).rowwise().sum().array();
    const Eigen::ArrayXd a = 1.0 + d;
    // Adding j alone: diag(C1) = diag(C) - u_j.^2 / (1 + d_j).
    const Eigen::ArrayXXd after_add =
        (-(U.array().square().colwise() / a)).rowwise() + c_diag.transpose();
    const std::vector<char> in = membership(n, chosen);
    double best = current * (1.0 - 1e-10);
    int best_slot = -1, best_j = -1;
    for (size_t s = 0; s < chosen.size(); ++s) {
      const Eigen::ArrayXd obj = swap_objectives(rows, U, d, a, after_add, chosen[s], q, ref);
      for (Eigen::Index j = 0; j < n; ++j)
        if (!in[static_cast<size_t>(j)] && obj[j] < best) best = obj[j], best_slot = static_cast<int>(s), best_j = static_cast<int>(j);
    }
    if (best_slot < 0) break;
    chosen[static_cast<size_t>(best_slot)] = best_j;
    ++swaps;
  }
  return swaps;
}

DesignOptions checked_design_options(double count, double sigma, const FreeMask& free, std::string_view criterion,
                                     double grid_step_mm, double guard_mm, bool cli) {
  const auto name = [cli](const char* flag, const char* arg) { return cli ? std::string(flag) : std::string(arg); };
  DesignOptions d;
  d.count = static_cast<int>(check_bound(count, limits::kDesignPoses, name("--count", "count")));
  d.sigma = check_bound(sigma, limits::kEncoderSigma, name("--sigma", "sigma"));
  d.free = free;
  const auto c = parse_criterion(criterion);
  if (!c)
    throw InputError(
        fmt::format("{}: '{}' is not d, worst or positioning", name("--criterion", "criterion"), criterion));
  d.criterion = *c;
  d.grid_step_mm = check_bound(grid_step_mm, limits::kGridStep, name("--grid-step", "grid_step"));
  d.guard.reach_mm = check_bound(guard_mm, limits::kDesignGuard, name("--guard", "guard"));
  return d;
}

Design design_poses(const Robot& nominal, const DesignOptions& o) {
  if (!(o.sigma > 0.0) || !std::isfinite(o.sigma))
    throw InputError(fmt::format("noise sigma must be a positive number of rad, got {}", o.sigma));
  const int p = static_cast<int>(o.free.count());
  if (p == 0) throw InputError("no free parameters: nothing to design for");
  if (o.count < p)
    throw InputError(fmt::format("{} poses cannot identify {} free parameters (need at least {})",
                                 o.count, p, p));
  Design out;
  std::vector<Eigen::Vector2d> cand = reachable_grid(nominal, o.grid_step_mm, o.guard);
  if (o.admissible) std::erase_if(cand, [&](const Eigen::Vector2d& p) { return !o.admissible(p); });
  out.candidates = static_cast<int>(cand.size());
  if (o.count > out.candidates)
    throw InputError(fmt::format("{} poses requested but the grid of step {} mm has only {} reachable "
                                 "candidates{} (use a finer step or fewer poses)",
                                 o.count, o.grid_step_mm, out.candidates,
                                 o.admissible ? " inside the safety limits" : ""));
  const Eigen::MatrixXd rows = information_rows(nominal, o.free, cand);
  if (!std::isfinite(bounds_from_rows(rows, nominal.geometry, o.free, o.sigma).log_det))
    throw InputError(fmt::format("free parameters {} cannot be identified from any poses: encoder angles "
                                 "cannot see a 2-D similarity, fix 4 base coordinates (e.g. --fix xa1,ya1,xa2,ya2)",
                                 format_param_list(o.free)));
  // Work in scaled units (all mm) so that C_kk of the scaled rows are the
  // scaled variances of the worst criterion (fisher.hpp).
  const Eigen::VectorXd s = parameter_scale(nominal.geometry, o.free);
  Eigen::MatrixXd rows_s = rows;
  for (Eigen::Index k = 0; k < rows_s.cols(); ++k) rows_s.col(k) /= s[k];

  auto poses_of = [&](const std::vector<int>& idx) {
    std::vector<Eigen::Vector2d> ps;
    for (int j : idx) ps.push_back(cand[static_cast<size_t>(j)]);
    return ps;
  };
  auto bounds_of = [&](const std::vector<int>& idx) {
    Eigen::MatrixXd r(static_cast<Eigen::Index>(idx.size()), rows.cols());
    for (size_t k = 0; k < idx.size(); ++k) r.row(static_cast<Eigen::Index>(k)) = rows.row(idx[k]);
    return bounds_from_rows(r, nominal.geometry, o.free, o.sigma);
  };

  const bool worst_stages = o.criterion != Criterion::kDOptimal;  // positioning starts from the worst design
  const int stages = design_stages(o.criterion);
  int stages_done = 0;
  const auto stage_done = [&] {
    if (o.progress) o.progress(++stages_done, stages);
  };
  std::vector<int> chosen = greedy_d_optimal(rows_s, o.count);
  stage_done();
  out.start = poses_of(chosen);
  out.start_bounds = bounds_of(chosen);
  std::vector<int> best = chosen;
  double best_value = criterion_value(o.criterion, out.start_bounds);
  auto keep_if_better = [&] {
    const double v = criterion_value(o.criterion, bounds_of(chosen));
    if (v < best_value) best_value = v, best = chosen;
  };
  out.exchanges += exchange_d_optimal(rows_s, chosen, o.max_exchanges);
  keep_if_better();
  stage_done();
  if (worst_stages) {
    for (int q : {1, 4, 16, 0}) {
      out.exchanges += exchange_variances(rows_s, chosen, q, o.max_exchanges);
      keep_if_better();
      stage_done();
    }
  }
  if (o.criterion == Criterion::kPositioning) {
    out.exchanges += positioning_stage(nominal, o, cand, best, out.positioning_bound_um);
    stage_done();
  }
  out.poses = poses_of(best);
  out.bounds = bounds_of(best);
  return out;
}

}  // namespace gpm::calib::excitation
