// The positioning criterion of excitation design (positioning_design.hpp).
// The exchange: for chosen pose i, removing it gives
//   C- = C + u u' / (1 - d_i),  u = C g_i, d_i = g_i' C g_i,
// and adding candidate j to the rest gives
//   trace(W C+) = trace(W C-) - (v_j' W v_j) / (1 + g_j' v_j),  v_j = C- g_j,
// so one product of the candidates' rows with C- prices every swap of i.
#include "calib/excitation/positioning_design.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include <Eigen/Cholesky>
#include <fmt/format.h>

#include "calib/excitation/fisher.hpp"
#include "models/errors.hpp"
#include "models/kinematics.hpp"

namespace gpm::calib::excitation {
namespace {

// The parameter index of each free column, in index order.
std::vector<int> free_index(const FreeMask& free) {
  std::vector<int> index;
  for (int k = 0; k < kNumParams; ++k)
    if (free.test(static_cast<size_t>(k))) index.push_back(k);
  return index;
}

// The chosen rows, scaled (rows' columns / column_scale, times row_weight).
Eigen::MatrixXd scaled_rows(const Eigen::MatrixXd& rows, const PositioningCriterion& c) {
  return c.row_weight * rows * c.column_scale.cwiseInverse().asDiagonal();
}

// C = F^-1 of the chosen scaled rows with the prior; nullopt where singular.
std::optional<Eigen::MatrixXd> covariance(const Eigen::MatrixXd& G, const std::vector<int>& chosen,
                                          const PositioningCriterion& c) {
  Eigen::MatrixXd F = c.prior_information.asDiagonal();
  for (int j : chosen) F.selfadjointView<Eigen::Lower>().rankUpdate(G.row(j).transpose());
  F = F.selfadjointView<Eigen::Lower>();
  const Eigen::LLT<Eigen::MatrixXd> llt(F);
  if (llt.info() != Eigen::Success) return std::nullopt;
  Eigen::MatrixXd C = llt.solve(Eigen::MatrixXd::Identity(F.rows(), F.cols()));
  if (!C.allFinite()) return std::nullopt;
  return C;
}

double bound_of(const Eigen::MatrixXd& W, const Eigen::MatrixXd& C) {
  return std::sqrt(std::max(W.cwiseProduct(C).sum(), 0.0)) * 1e3;
}

}  // namespace

Eigen::MatrixXd rows_with_cyclic_error(const Robot& robot, const FreeMask& free,
                                       const std::vector<Eigen::Vector2d>& poses) {
  const std::vector<int> index = free_index(free);
  std::array<Eigen::Index, 3> col{};
  for (int i = 0; i < kNumChains; ++i) {
    const auto at = std::find(index.begin(), index.end(), dth(i));
    if (at == index.end())
      throw InputError(fmt::format("the positioning criterion needs dth{} free: the encoders' error once per joint "
                                   "revolution is told from the geometry through the offsets' columns",
                                   i + 1));
    col[static_cast<size_t>(i)] = at - index.begin();
  }
  const Eigen::MatrixXd rows = information_rows(robot, free, poses);
  Eigen::MatrixXd out(rows.rows(), rows.cols() + 6);
  out.leftCols(rows.cols()) = rows;
  for (Eigen::Index j = 0; j < rows.rows(); ++j) {
    const JointAngles q = inverse_kinematics(robot.geometry, poses[static_cast<size_t>(j)], robot.branch);
    const Eigen::Vector3d theta_m = readings_from_active(robot.geometry, q.theta_a);
    for (int i = 0; i < kNumChains; ++i) {
      const double g = rows(j, col[static_cast<size_t>(i)]);
      out(j, rows.cols() + 2 * i) = -g * std::sin(theta_m[i]);
      out(j, rows.cols() + 2 * i + 1) = -g * std::cos(theta_m[i]);
    }
  }
  return out;
}

PositioningCriterion positioning_criterion(const Robot& robot, const FreeMask& free, const PositioningPrior& prior,
                                           double sigma, const Eigen::MatrixXd& rows) {
  const double s = prior.cyclic_prior_rad > 0.0 ? prior.cyclic_prior_rad
                                                : robot.data_sheet.joint_harmonic_max_rad() / std::sqrt(2.0);
  if (!(s > 0.0))
    throw InputError(fmt::format("positioning criterion: the robot's data sheet states no error once per joint "
                                 "revolution (encoder_accuracy_rad, transmission_error_rad) and none is given ({} rad): "
                                 "nothing to tell from the geometry; use the worst or d criterion",
                                 prior.cyclic_prior_rad));
  if (!(prior.samples_per_pose > 0.0) || !(sigma > 0.0))
    throw InputError(fmt::format("positioning criterion: the readings per pose ({}) and the noise ({} rad) must be "
                                 "positive",
                                 prior.samples_per_pose, sigma));
  const Eigen::Index p = rows.cols(), ng = p - 6;
  PositioningCriterion c;
  c.row_weight = std::sqrt(prior.samples_per_pose) / sigma;
  c.column_scale = rows.colwise().norm().transpose();
  for (Eigen::Index k = 0; k < p; ++k)
    if (!(c.column_scale[k] > 0.0)) c.column_scale[k] = 1.0;
  const Eigen::Matrix<double, kNumParams, kNumParams> W15 =
      positioning_weight(robot, WorkspaceDisc{robot.home, prior.radius_mm, prior.step_mm});
  c.weight = Eigen::MatrixXd::Zero(p, p);
  const std::vector<int> index = free_index(free);
  // C in scaled columns is S C S: trace(W C) = trace(S^-1 W S^-1 (S C S)).
  for (Eigen::Index a = 0; a < ng; ++a)
    for (Eigen::Index b = 0; b < ng; ++b)
      c.weight(a, b) = W15(index[static_cast<size_t>(a)], index[static_cast<size_t>(b)]) /
                       (c.column_scale[a] * c.column_scale[b]);
  c.prior_information = Eigen::VectorXd::Zero(p);
  for (Eigen::Index k = ng; k < p; ++k)
    c.prior_information[k] = 1.0 / std::pow(c.column_scale[k] * s, 2);
  return c;
}

double positioning_bound_um(const Eigen::MatrixXd& rows, const std::vector<int>& chosen,
                            const PositioningCriterion& c) {
  const auto C = covariance(scaled_rows(rows, c), chosen, c);
  return C ? bound_of(c.weight, *C) : std::numeric_limits<double>::infinity();
}

int exchange_positioning(const Eigen::MatrixXd& rows, std::vector<int>& chosen, const PositioningCriterion& c,
                         int max_swaps) {
  const Eigen::MatrixXd G = scaled_rows(rows, c);
  std::vector<char> in(static_cast<size_t>(G.rows()), 0);
  for (int j : chosen) in[static_cast<size_t>(j)] = 1;
  auto C = covariance(G, chosen, c);
  if (!C) return 0;
  double current = bound_of(c.weight, *C);
  int swaps = 0;
  for (bool swapped = true; swapped && swaps < max_swaps;) {
    swapped = false;
    for (size_t s = 0; s < chosen.size() && swaps < max_swaps; ++s) {
      const Eigen::VectorXd u = *C * G.row(chosen[s]).transpose();
      const double d = G.row(chosen[s]).dot(u);
      if (!(1.0 - d > 1e-9)) continue;  // the rest alone would be singular
      const Eigen::MatrixXd C_minus = *C + u * u.transpose() / (1.0 - d);
      const Eigen::MatrixXd V = G * C_minus;
      const Eigen::ArrayXd gain = ((V * c.weight).cwiseProduct(V).rowwise().sum().array()) /
                                  (1.0 + V.cwiseProduct(G).rowwise().sum().array());
      const double base = c.weight.cwiseProduct(C_minus).sum();
      int best = -1;
      double best_value = current * (1.0 - 1e-9);
      for (Eigen::Index j = 0; j < G.rows(); ++j) {
        if (in[static_cast<size_t>(j)]) continue;
        const double value = std::sqrt(std::max(base - gain[j], 0.0)) * 1e3;
        if (value < best_value) best_value = value, best = static_cast<int>(j);
      }
      if (best < 0) continue;
      std::vector<int> trial = chosen;
      trial[s] = best;
      const auto C_trial = covariance(G, trial, c);
      if (!C_trial || bound_of(c.weight, *C_trial) >= current) continue;  // the update's rounding misled it
      in[static_cast<size_t>(chosen[s])] = 0, in[static_cast<size_t>(best)] = 1;
      chosen = std::move(trial);
      C = C_trial;
      current = bound_of(c.weight, *C);
      ++swaps, swapped = true;
    }
  }
  return swaps;
}

}  // namespace gpm::calib::excitation
