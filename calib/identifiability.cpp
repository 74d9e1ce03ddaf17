#include "calib/identifiability.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include <Eigen/QR>
#include <Eigen/SVD>
#include <fmt/format.h>

#include "calib/residuals.hpp"
#include "models/errors.hpp"

namespace gpm::calib {

Eigen::Matrix<double, kNumParams, 4> gauge_generators(const Geometry& g) {
  Eigen::Matrix<double, kNumParams, 4> G = Eigen::Matrix<double, kNumParams, 4>::Zero();
  const Eigen::Vector2d A1 = g.A(0);
  for (int i = 0; i < kNumChains; ++i) {
    const Eigen::Vector2d r = g.A(i) - A1;
    G(xa(i), 0) = 1.0;  // translation x
    G(ya(i), 1) = 1.0;  // translation y
    G(xa(i), 2) = -r.y();  // rotation about A1: A_i moves along perp(A_i - A1) ...
    G(ya(i), 2) = r.x();
    G(dth(i), 2) = 1.0;    // ... and every active angle, hence every offset, turns by the same angle
    G(xa(i), 3) = r.x();   // scale about A1
    G(ya(i), 3) = r.y();
    G(la(i), 3) = g.la_(i);
    G(lb(i), 3) = g.lb_(i);
  }
  return G;
}

Eigen::MatrixXd ml_jacobian(const std::vector<Eigen::Vector3d>& theta_m, const Geometry& g) {
  Eigen::MatrixXd J(static_cast<Eigen::Index>(theta_m.size()), kNumParams);
  Eigen::Matrix<double, 1, kNumParams, Eigen::RowMajor> row;
  for (size_t j = 0; j < theta_m.size(); ++j) {
    std::unique_ptr<ceres::CostFunction> f(make_residual(Cost::kML, theta_m[j]));
    const double* params[] = {g.values.data()};
    double* jac[] = {row.data()};
    double r = 0.0;
    if (!f->Evaluate(params, &r, jac)) row.setConstant(std::numeric_limits<double>::quiet_NaN());
    J.row(static_cast<Eigen::Index>(j)) = row;
  }
  return J;
}

namespace {

// Words for a set of involved gauge generators.
std::string describe_gauge(const std::array<bool, 4>& on) {
  std::vector<std::string> what, effect;
  if (on[0] && on[1]) what.push_back("translation");
  else if (on[0]) what.push_back("translation along x");
  else if (on[1]) what.push_back("translation along y");
  if (on[3]) {
    what.push_back(on[2] ? "scale and rotation about A1" : "scale about A1");
    effect.push_back("all lengths grow together");
  } else if (on[2]) {
    what.push_back("rotation about A1");
  }
  if (on[2]) effect.push_back("all offsets shift together");
  if (on[0] || on[1] || on[2] || on[3]) effect.push_back("the free base coordinates follow");
  std::string out;
  for (size_t k = 0; k < what.size(); ++k) out += (k ? " plus " : "") + what[k];
  out += ": ";
  for (size_t k = 0; k < effect.size(); ++k) out += (k ? ", " : "") + effect[k];
  return out;
}

// The ML Jacobian's columns of the free parameters, each scaled to unit
// norm (col_norm: the scales; a zero column, a parameter no sample sees,
// stays zero), padded with zero rows to at least as many rows as columns.
Eigen::MatrixXd scaled_free_jacobian(const std::vector<Eigen::Vector3d>& theta_m, const Geometry& g,
                                     const std::vector<int>& free_index, Eigen::VectorXd& col_norm) {
  const auto p = static_cast<Eigen::Index>(free_index.size());
  const Eigen::MatrixXd J_all = ml_jacobian(theta_m, g);
  Eigen::MatrixXd J(J_all.rows(), p);
  col_norm.resize(p);
  for (Eigen::Index k = 0; k < p; ++k) {
    J.col(k) = J_all.col(free_index[static_cast<size_t>(k)]);
    col_norm[k] = J.col(k).norm();
    if (col_norm[k] > 0.0) J.col(k) /= col_norm[k];
  }
  // Pad to at least p rows so the SVD has p singular values.
  if (J.rows() < p) {
    Eigen::MatrixXd Jp = Eigen::MatrixXd::Zero(p, p);
    Jp.topRows(J.rows()) = J;
    J = Jp;
  }
  return J;
}

// out.singular_values, rank (kRankTolerance) and condition number from the SVD of the scaled Jacobian.
void rank_and_condition(const Eigen::JacobiSVD<Eigen::MatrixXd>& svd, Identifiability& out) {
  const Eigen::Index p = svd.singularValues().size();
  out.singular_values = svd.singularValues();
  const double smax = out.singular_values[0];
  out.rank = 0;
  for (Eigen::Index k = 0; k < p; ++k)
    if (std::isfinite(out.singular_values[k]) && out.singular_values[k] > kRankTolerance * smax) ++out.rank;
  const double smin = out.singular_values[p - 1];
  out.condition_number = smin > 0.0 ? smax / smin : std::numeric_limits<double>::infinity();
}

// Which gauge generators of g (gauge_generators) the null directions N
// (embedded in the 15 slots) involve; fit: the relative residual of N
// spanned by the generators (small: the null directions are gauge motions).
std::array<bool, 4> gauge_involved(const Geometry& g, const Eigen::MatrixXd& N, double& fit) {
  const Eigen::Matrix<double, kNumParams, 4> G = gauge_generators(g);
  const Eigen::MatrixXd C = G.colPivHouseholderQr().solve(N);
  fit = (G * C - N).norm() / std::max(N.norm(), 1e-300);
  std::array<bool, 4> on{};
  for (int q = 0; q < 4; ++q) {
    const double contribution = (G.col(q) * C.row(q)).norm();
    on[static_cast<size_t>(q)] = contribution > 1e-3 * N.norm();
  }
  return on;
}

// out.description and advice for k_null null directions that are gauge motions (generators on).
void describe_gauge_null(const std::array<bool, 4>& on, Eigen::Index k_null, const FreeMask& free,
                         Identifiability& out) {
  out.description = fmt::format("{} unobservable direction{} ({})", k_null, k_null > 1 ? "s" : "",
                                describe_gauge(on));
  // Which free base coordinate moves most along the (first) null direction.
  int best = -1;
  double best_v = 0.0;
  for (size_t k = 0; k < out.free_index.size(); ++k) {
    const int i = out.free_index[k];
    if (i > kYa3) continue;
    const double v = out.null_vectors.rowwise().norm()[static_cast<Eigen::Index>(k)];
    if (v > best_v) best_v = v, best = i;
  }
  if (k_null == 1 && best >= 0) {
    out.advice = fmt::format("fix {} at its known value too (e.g. --fix {},{})", param_name(best),
                             format_param_list(~free), param_name(best));
  } else {
    out.advice = fmt::format("fix {} more base coordinate{} (encoder angles cannot see a 2-D "
                             "similarity; the default --fix xa1,ya1,xa2,ya2 removes it)",
                             k_null, k_null > 1 ? "s" : "");
  }
}

// out.description and advice for k_null null directions the samples do not
// excite: the (up to 4) largest parts of the first one.
void describe_unexcited(Eigen::Index k_null, Identifiability& out) {
  const Eigen::VectorXd v = out.null_vectors.col(0) / out.null_vectors.col(0).norm();
  std::vector<std::pair<double, int>> parts;
  for (Eigen::Index k = 0; k < v.size(); ++k) parts.emplace_back(-std::abs(v[k]), static_cast<int>(k));
  std::sort(parts.begin(), parts.end());
  std::string comb;
  for (size_t q = 0; q < parts.size() && q < 4; ++q) {
    if (-parts[q].first < 0.05) break;
    const int k = parts[q].second;
    comb += fmt::format("{}{} {:+.2f}", q ? ", " : "", param_name(out.free_index[static_cast<size_t>(k)]), v[k]);
  }
  out.description = fmt::format("{} unobservable direction{} the samples do not excite ({})", k_null,
                                k_null > 1 ? "s" : "", comb);
  out.advice = "add samples spread over the workspace, or fix one of these parameters";
}

// out.null_vectors in parameter units from the SVD (col_norm: the column
// scales), then their description: gauge motions or unexcited parameters.
void describe_null_space(const Eigen::JacobiSVD<Eigen::MatrixXd>& svd, const Eigen::VectorXd& col_norm,
                         const Geometry& g, const FreeMask& free, Identifiability& out) {
  const Eigen::Index p = col_norm.size();
  const Eigen::Index k_null = p - out.rank;
  out.null_vectors = svd.matrixV().rightCols(k_null);
  for (Eigen::Index k = 0; k < p; ++k)
    if (col_norm[k] > 0.0) out.null_vectors.row(k) /= col_norm[k];
  // Are they gauge motions? Fit each null vector (embedded in 15 slots) with
  // the generators restricted to keep the fixed parameters fixed.
  Eigen::MatrixXd N = Eigen::MatrixXd::Zero(kNumParams, k_null);
  for (Eigen::Index k = 0; k < p; ++k) N.row(out.free_index[static_cast<size_t>(k)]) = out.null_vectors.row(k);
  double fit = 0.0;
  const std::array<bool, 4> on = gauge_involved(g, N, fit);
  if (fit < 1e-3)
    describe_gauge_null(on, k_null, free, out);
  else
    describe_unexcited(k_null, out);
}

}  // namespace

Identifiability analyse_identifiability(const std::vector<Eigen::Vector3d>& theta_m,
                                        const Geometry& g, const FreeMask& free) {
  Identifiability out;
  for (int i = 0; i < kNumParams; ++i)
    if (free.test(static_cast<size_t>(i))) out.free_index.push_back(i);
  const auto p = static_cast<Eigen::Index>(out.free_index.size());
  out.free_count = static_cast<int>(p);
  if (p == 0) {
    out.diagnosis = "rank 0 of 0: no free parameters";
    return out;
  }
  Eigen::VectorXd col_norm;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(scaled_free_jacobian(theta_m, g, out.free_index, col_norm),
                                              Eigen::ComputeFullV);
  rank_and_condition(svd, out);
  if (out.rank == p) {
    out.diagnosis = fmt::format("rank {} of {}: all free parameters identifiable (condition number {:.3g})",
                                out.rank, p, out.condition_number);
    return out;
  }
  describe_null_space(svd, col_norm, g, free, out);
  out.diagnosis = fmt::format("rank {} of {}: {}; {}", out.rank, p, out.description, out.advice);
  return out;
}

void require_identifiable(const Identifiability& id, const FreeMask& free) {
  const int p = static_cast<int>(free.count());
  if (id.rank >= p) return;
  throw InputError(fmt::format(
      "--fix: the {} free parameters ({}) are not identifiable from encoder angles (rank {} of "
      "{}): {}; {}, or pass --allow-rank-deficient for a minimum-norm solution",
      p, format_param_list(free), id.rank, p, id.description, id.advice));
}

}  // namespace gpm::calib
