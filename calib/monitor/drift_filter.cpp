#include "calib/monitor/drift_filter.hpp"

#include <algorithm>
#include <cmath>

namespace gpm::calib::monitor {
namespace {

// The readings with the estimated cyclic error removed:
// theta_m_i - (a_i sin theta_m_i + b_i cos theta_m_i).
Eigen::Vector3d without_cyclic(const MonitorModel& m, const std::array<double, kNumCyclic>& cyc,
                               const Eigen::Vector3d& theta_m) {
  if (m.cyclic_index < 0) return theta_m;
  Eigen::Vector3d t = theta_m;
  for (int i = 0; i < 3; ++i)
    t[i] -= cyc[static_cast<size_t>(2 * i)] * std::sin(theta_m[i]) + cyc[static_cast<size_t>(2 * i + 1)] * std::cos(theta_m[i]);
  return t;
}

// h = dr/du (zero for the rate; for the cyclic coefficients dr/dtheta_i =
// dr/ddth_i times -sin, -cos theta_m_i), P h' and s = sigma^2 + h P h'.
double innovation_variance(const MonitorModel& m, double noise_scale, const StateMatrix& P, const ParamRow& g,
                           const Eigen::Vector3d& theta_m, const Eigen::Vector3d& tension,
                           std::array<double, kMaxState>& Ph) {
  std::array<double, kMaxState> h{};
  for (int k = 0; k < m.n_free; ++k) h[static_cast<size_t>(k)] = g[m.free_index[static_cast<size_t>(k)]] / m.scale[static_cast<size_t>(k)];
  if (m.cyclic_index >= 0)
    for (int i = 0; i < 3; ++i) {
      const auto k = static_cast<size_t>(m.cyclic_index + 2 * i);
      h[k] = -g[dth(i)] * std::sin(theta_m[i]) / m.scale[k];
      h[k + 1] = -g[dth(i)] * std::cos(theta_m[i]) / m.scale[k + 1];
    }
  if (m.clearance_index >= 0)
    for (int i = 0; i < 3; ++i) h[static_cast<size_t>(m.clearance_index + i)] = tension[i] * g[lb(i)];
  double hPh = 0.0;
  for (int k = 0; k < m.n_state; ++k) {
    double acc = 0.0;
    for (int l = 0; l < m.n_state; ++l) acc += P(k, l) * h[static_cast<size_t>(l)];
    Ph[static_cast<size_t>(k)] = acc;
    hPh += h[static_cast<size_t>(k)] * acc;
  }
  const double sigma = noise_scale * m.sigma_rad;  // the learnt reading noise (1 until learnt)
  return sigma * sigma + hPh;
}

}  // namespace

void filter_predict(const MonitorModel& m, Geometry& x, double& rate, StateMatrix& P, double dt) {
  if (!(dt > 0.0)) return;
  const int n = m.n_state, rho = m.rate_index;
  if (rho >= 0) {
    for (int k = 0; k < m.n_free; ++k)
      x[m.free_index[static_cast<size_t>(k)]] += m.growth[static_cast<size_t>(k)] * rate * dt / m.scale[static_cast<size_t>(k)];
    // P <- F P F' with F = I + dt v e_rho'.
    std::array<double, kMaxState> c{};
    for (int k = 0; k < n; ++k) c[static_cast<size_t>(k)] = P(k, rho);
    const double c_rr = P(rho, rho);
    for (int k = 0; k < n; ++k)
      for (int l = 0; l < n; ++l) {
        const double vk = m.growth[static_cast<size_t>(k)], vl = m.growth[static_cast<size_t>(l)];
        P(k, l) += dt * (vk * c[static_cast<size_t>(l)] + c[static_cast<size_t>(k)] * vl) + dt * dt * c_rr * vk * vl;
      }
    // Process noise of the rate, integrated into the parameters.
    const double q = m.rate_noise;
    for (int k = 0; k < n; ++k) {
      const double vk = k == rho ? 0.0 : m.growth[static_cast<size_t>(k)];
      for (int l = 0; l < n; ++l) {
        const double vl = l == rho ? 0.0 : m.growth[static_cast<size_t>(l)];
        double add = q * dt * dt * dt / 3.0 * vk * vl;
        if (k == rho && l == rho) add = q * dt;
        else if (k == rho) add = q * dt * dt / 2.0 * vl;
        else if (l == rho) add = q * dt * dt / 2.0 * vk;
        P(k, l) += add;
      }
    }
  }
  for (int k = 0; k < n; ++k) P(k, k) += m.drift_rate[static_cast<size_t>(k)] * dt;
  // Keep each variance below its ceiling (D P D stays positive semi-definite).
  for (int k = 0; k < n; ++k)
    if (P(k, k) > m.variance_cap[static_cast<size_t>(k)]) {
      const double f = std::sqrt(m.variance_cap[static_cast<size_t>(k)] / P(k, k));
      for (int l = 0; l < n; ++l) P(k, l) *= f, P(l, k) *= f;
    }
}

// The geometry a sample is read against: the estimate with its clearance shift.
static Geometry shifted(const Geometry& x, const std::array<double, 3>& clearance, const Eigen::Vector3d& tension) {
  Geometry g = x;
  for (int i = 0; i < 3; ++i) g[lb(i)] += clearance[static_cast<size_t>(i)] * tension[i];
  return g;
}

bool filter_innovation(const MonitorModel& m, const FilterWindow& d, double t_s, const Eigen::Vector3d& theta_m,
                       const Eigen::Vector3d& tension, double& z, ParamRow& dz, double r_map, double* r_out,
                       double* z_filter) {
  Geometry x = d.estimate;
  double rate = d.growth_rate;
  StateMatrix P = d.P;
  if (d.filtered > 0) filter_predict(m, x, rate, P, t_s - d.t_last_update);
  double r = 0.0;
  ParamRow g;
  if (!ml_residual_and_gradient(shifted(x, d.clearance, tension), without_cyclic(m, d.cyclic, theta_m), r, g)) return false;
  if (r_out) *r_out = r;
  r -= r_map;
  std::array<double, kMaxState> Ph{};
  const double s = innovation_variance(m, d.noise_scale, P, g, theta_m, tension, Ph);
  const double sqrt_s = std::sqrt(s);
  z = r / sqrt_s;
  dz = g / sqrt_s;
  if (z_filter) {
    const double sigma = d.noise_scale * m.sigma_rad;
    *z_filter = std::sqrt(std::max(s - sigma * sigma, 0.0) / s);
  }
  return true;
}

void filter_update(const MonitorModel& m, FilterWindow& d, double t_s, const Eigen::Vector3d& theta_m,
                   const Eigen::Vector3d& tension, double r_map) {
  if (d.filtered > 0) filter_predict(m, d.estimate, d.growth_rate, d.P, std::max(t_s - d.t_last_update, 0.0));
  d.t_last_update = std::max(t_s, d.t_last_update);
  double r = 0.0;
  ParamRow g;
  if (!ml_residual_and_gradient(shifted(d.estimate, d.clearance, tension), without_cyclic(m, d.cyclic, theta_m), r, g)) return;
  r -= r_map;
  std::array<double, kMaxState> Ph{};
  const double s = innovation_variance(m, d.noise_scale, d.P, g, theta_m, tension, Ph);
  for (int k = 0; k < m.n_state; ++k) {
    const double du = -Ph[static_cast<size_t>(k)] / s * r;
    if (k == m.rate_index) d.growth_rate += du;
    else if (m.clearance_index >= 0 && k >= m.clearance_index)
      d.clearance[static_cast<size_t>(k - m.clearance_index)] += du / m.scale[static_cast<size_t>(k)];
    else if (m.cyclic_index >= 0 && k >= m.cyclic_index)
      d.cyclic[static_cast<size_t>(k - m.cyclic_index)] += du / m.scale[static_cast<size_t>(k)];
    else d.estimate[m.free_index[static_cast<size_t>(k)]] += du / m.scale[static_cast<size_t>(k)];
  }
  for (int k = 0; k < m.n_state; ++k)
    for (int l = 0; l <= k; ++l) {
      const double v = d.P(k, l) - Ph[static_cast<size_t>(k)] * Ph[static_cast<size_t>(l)] / s;
      d.P(k, l) = v;
      d.P(l, k) = v;
    }
  ++d.filtered;
}

}  // namespace gpm::calib::monitor
