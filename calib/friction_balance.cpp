// Each drive's friction from the hub's force balance (calib/friction_balance.hpp).
#include "calib/friction_balance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Cholesky>
#include <fmt/format.h>

#include "calib/reading_rates.hpp"
#include "calib/robust_loss.hpp"
#include "models/errors.hpp"
#include "models/kinematics.hpp"

namespace gpm::calib {
namespace {

constexpr int kFrictionColumns = 6;     // F1 F2 F3 b1 b2 b3
constexpr int kColumns = 12;            // with the cogging: A1 A2 A3 B1 B2 B3
constexpr int kReweightings = 8;        // IRLS passes
constexpr std::size_t kBlocks = 10;     // the jackknife's stretches of the path
constexpr std::size_t kMinSamples = 20 * kBlocks;

// Rows of kFrictionColumns, or kColumns with the cogging.
using Row = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kColumns, 1>;
using Normal = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kColumns, kColumns>;

// One sample's two rows of the balance: coefficients of (F, b) and the right-hand side, per axis.
struct SampleRows {
  Row coef[2];
  double rhs[2] = {0.0, 0.0};
};

// The rows of sample j, or false where the pose is near a singularity (some |S_i| < min_sin) or has no forward kinematics.
bool sample_rows(const Geometry& g, const BalanceSamples& s, const TransmissionLoad& load, double hub_mass_kg,
                 std::size_t j, double min_sin, SampleRows& out) {
  const Eigen::Vector3d theta_a = active_from_readings(g, s.theta_m[j]);
  const std::optional<ForwardResult> fk = forward_kinematics(g, theta_a);
  if (!fk) return false;
  const bool cogging = s.cogging_per_rad > 0.0;
  for (int k = 0; k < 2; ++k) {
    out.coef[k].setZero(cogging ? kColumns : kFrictionColumns);
    out.rhs[k] = -hub_mass_kg * s.hub_accel_m_s2[j][k];
  }
  for (int i = 0; i < 3; ++i) {
    const auto ii = static_cast<std::size_t>(i);
    const double S = std::sin(fk->theta_b[i] - theta_a[i]);
    if (std::abs(S) < min_sin) return false;
    const double la_S = 1e-3 * g.la_(i) * S;
    const double omega = s.omega[j][i];
    const double sgn = friction_sign(load, omega);
    const double tau_net = s.tau[j][i] - load.inertia_kg_m2[ii] * s.alpha[j][i];
    const Eigen::Vector2d u(std::cos(fk->theta_b[i]), std::sin(fk->theta_b[i]));
    for (int k = 0; k < 2; ++k) {
      out.coef[k][i] = u[k] * sgn / la_S;
      out.coef[k][3 + i] = u[k] * omega / la_S;
      out.rhs[k] += u[k] * tau_net / la_S;
    }
    if (!cogging) continue;
    const double a = s.cogging_per_rad * s.theta_m[j][i];
    for (int k = 0; k < 2; ++k) {
      out.coef[k][6 + i] = -u[k] * std::sin(a) / la_S;
      out.coef[k][9 + i] = -u[k] * std::cos(a) / la_S;
    }
  }
  return true;
}

// The weighted normal equations M'WM x = M'W y of the rows [first, last).
struct NormalEquations {
  Normal N;
  Row b;
};
NormalEquations normal_equations(const std::vector<SampleRows>& rows, const std::vector<double>& w, std::size_t first,
                                 std::size_t last) {
  NormalEquations ne;
  const Eigen::Index columns = rows.front().coef[0].size();
  ne.N.setZero(columns, columns);
  ne.b.setZero(columns);
  for (std::size_t q = first; q < last; ++q)
    for (int k = 0; k < 2; ++k) {
      const double wk = w[2 * q + static_cast<std::size_t>(k)];
      ne.N.selfadjointView<Eigen::Lower>().rankUpdate(rows[q].coef[k], wk);
      ne.b += wk * rows[q].rhs[k] * rows[q].coef[k];
    }
  ne.N.triangularView<Eigen::StrictlyUpper>() = ne.N.transpose();
  return ne;
}

// The rows' residuals y - M x (N), two a sample.
std::vector<double> residuals(const std::vector<SampleRows>& rows, const Row& x) {
  std::vector<double> res(2 * rows.size());
  for (std::size_t q = 0; q < rows.size(); ++q)
    for (int k = 0; k < 2; ++k) res[2 * q + static_cast<std::size_t>(k)] = rows[q].rhs[k] - rows[q].coef[k].dot(x);
  return res;
}

// Huber's weights w of the rows' residuals at x (95 % efficiency tuning), at their robust sigma.
void reweight(const std::vector<SampleRows>& rows, const Row& x, std::vector<double>& w) {
  const std::vector<double> res = residuals(rows, x);
  const double scale = default_tuning(LossKind::kHuber) * std::max(robust_sigma(res), 1e-12);
  for (std::size_t q = 0; q < res.size(); ++q) w[q] = std::min(1.0, scale / std::max(std::abs(res[q]), 1e-300));
}

// The variance of the estimate by the delete-a-block jackknife over kBlocks
// stretches of the path (the rows' errors are correlated along it: the
// drives' ringing, a misfit that follows the motion; (M'WM)^-1 s^2 would
// take them as independent), all the normal equations of every row.
Row jackknife_variance(const std::vector<SampleRows>& rows, const std::vector<double>& w, const NormalEquations& all) {
  std::array<Row, kBlocks> x_without;
  Row mean = Row::Zero(all.b.size());
  for (std::size_t k = 0; k < kBlocks; ++k) {
    const NormalEquations part = normal_equations(rows, w, k * rows.size() / kBlocks, (k + 1) * rows.size() / kBlocks);
    x_without[k] = (all.N - part.N).ldlt().solve(all.b - part.b);
    mean += x_without[k] / static_cast<double>(kBlocks);
  }
  Row var = Row::Zero(all.b.size());
  for (const Row& xk : x_without) var += (xk - mean).cwiseAbs2();
  return var * (static_cast<double>(kBlocks - 1) / static_cast<double>(kBlocks));
}

}  // namespace

double cogging_torque(const BalanceFriction& f, int i, double theta_m, double cogging_per_rad) {
  const auto k = static_cast<std::size_t>(i);
  const double a = cogging_per_rad * theta_m;
  return f.cogging_Nm[k] * std::sin(a) + f.cogging_Nm[k + 3] * std::cos(a);
}

std::vector<Eigen::Vector2d> hub_accelerations(const Geometry& g, const std::vector<double>& t_s,
                                               const std::vector<Eigen::Vector3d>& theta_m, int alpha_span) {
  std::vector<Eigen::Vector3d> hub(theta_m.size(), Eigen::Vector3d::Zero());
  for (std::size_t j = 0; j < theta_m.size(); ++j) {
    const std::optional<ForwardResult> fk = forward_kinematics(g, active_from_readings(g, theta_m[j]));
    if (fk) hub[j] << 1e-3 * fk->p, 0.0;
    else if (j > 0) hub[j] = hub[j - 1];
  }
  RateOptions ro;
  ro.alpha_span = alpha_span;
  const ReadingRates rates = reading_rates(t_s, hub, ro);  // metres never wrap: |step| << pi
  std::vector<Eigen::Vector2d> a(theta_m.size());
  for (std::size_t j = 0; j < a.size(); ++j) a[j] = rates.alpha[j].head<2>();
  return a;
}

BalanceFriction friction_from_force_balance(const Geometry& g, const BalanceSamples& s, const TransmissionLoad& load,
                                            double hub_mass_kg, int skip_first, double min_sin) {
  const std::size_t n = s.theta_m.size();
  if (s.omega.size() != n || s.alpha.size() != n || s.tau.size() != n || s.hub_accel_m_s2.size() != n)
    throw InputError(fmt::format("friction from the force balance: {} readings but {} speeds, {} accelerations, {} "
                                 "torques, {} hub accelerations (one of each per reading)",
                                 n, s.omega.size(), s.alpha.size(), s.tau.size(), s.hub_accel_m_s2.size()));
  std::vector<SampleRows> rows;
  rows.reserve(n);
  SampleRows r;
  for (std::size_t j = static_cast<std::size_t>(std::max(0, skip_first)); j < n; ++j)
    if (sample_rows(g, s, load, hub_mass_kg, j, min_sin, r)) rows.push_back(r);
  if (rows.size() < kMinSamples)
    throw InputError(fmt::format("friction from the force balance: {} usable samples (at least {} needed away from "
                                 "the singularities)", rows.size(), kMinSamples));
  // Iteratively reweighted least squares: Huber weights at a scale from the residuals' MAD.
  std::vector<double> w(2 * rows.size(), 1.0);
  Row x;
  for (int pass = 0; pass <= kReweightings; ++pass) {
    const NormalEquations ne = normal_equations(rows, w, 0, rows.size());
    x = ne.N.ldlt().solve(ne.b);
    reweight(rows, x, w);
  }
  const NormalEquations all = normal_equations(rows, w, 0, rows.size());
  x = all.N.ldlt().solve(all.b);
  const Row var = jackknife_variance(rows, w, all);
  double sum_sq = 0.0;
  for (const double r : residuals(rows, x)) sum_sq += r * r;
  BalanceFriction out;
  for (std::size_t i = 0; i < 3; ++i) {
    const auto c = static_cast<Eigen::Index>(i);
    out.coulomb_Nm[i] = std::max(0.0, x[c]);
    out.viscous_Nm_s[i] = std::max(0.0, x[c + 3]);
    out.coulomb_sigma_Nm[i] = std::sqrt(var[c]);
    out.viscous_sigma_Nm_s[i] = std::sqrt(var[c + 3]);
  }
  out.cogging_sigma_Nm.fill(std::numeric_limits<double>::quiet_NaN());
  for (std::size_t k = 0; x.size() == kColumns && k < 6; ++k) {
    const auto c = static_cast<Eigen::Index>(kFrictionColumns + k);
    out.cogging_Nm[k] = x[c];
    out.cogging_sigma_Nm[k] = std::sqrt(var[c]);
  }
  out.residual_rms_N = std::sqrt(sum_sq / static_cast<double>(2 * rows.size()));
  out.tension_sigma_N = out.residual_rms_N * std::sqrt(2.0 / 3.0);
  out.samples = rows.size();
  return out;
}

}  // namespace gpm::calib
