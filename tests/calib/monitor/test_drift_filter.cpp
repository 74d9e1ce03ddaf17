// Tests of calib/monitor/drift_filter.cpp: the prediction equals the dense
// F P F' + Q of the constant-rate model; without process noise the Kalman
// updates equal the information form (P0^-1 + sum h'h / sigma^2)^-1 of the
// same samples; the innovation is r / sqrt(sigma^2 + h P h') by hand, and
// the filter's share of it sqrt(h P h' / s).
#include "calib/monitor/drift_filter.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "models/rng.hpp"
#include "tests/calib/monitor/circle_stream.hpp"

namespace gpm::calib::monitor {
namespace {

Eigen::MatrixXd used(const MonitorModel& m, const StateMatrix& P) { return P.topLeftCorner(m.n_state, m.n_state); }

TEST(DriftFilter, PredictionIsTheConstantRateModel) {
  MonitorSettings s;
  s.length_drift_mm = 0.001;
  const MonitorModel m = make_monitor_model(s);
  ASSERT_EQ(m.n_state, 12);
  ASSERT_EQ(m.rate_index, 11);
  const int n = m.n_state;
  Rng rng(3);
  Eigen::MatrixXd A(n, n);
  for (int k = 0; k < n; ++k)
    for (int l = 0; l < n; ++l) A(k, l) = 1e-4 * rng.normal();
  const Eigen::MatrixXd P0 = A * A.transpose() * 1e-3;  // small: no variance reaches its cap
  StateMatrix P = StateMatrix::Zero();
  P.topLeftCorner(n, n) = P0;
  Geometry x = s.geometry;
  double rate = 2e-4;
  const double dt = 0.37;
  filter_predict(m, x, rate, P, dt);
  // Dense F = I + dt v e_rho' and the integrated white rate noise.
  Eigen::MatrixXd F = Eigen::MatrixXd::Identity(n, n);
  Eigen::VectorXd v = Eigen::VectorXd::Zero(n);
  for (int k = 0; k < m.n_free; ++k) v[k] = m.growth[static_cast<size_t>(k)];
  F.col(m.rate_index) += dt * v;
  Eigen::VectorXd b = dt * dt / 2.0 * v;
  b[m.rate_index] = dt;
  Eigen::MatrixXd Q = Eigen::MatrixXd::Zero(n, n);
  Q.topLeftCorner(m.n_free, m.n_free) = dt * dt * dt / 3.0 * v.head(m.n_free) * v.head(m.n_free).transpose();
  Q.col(m.rate_index) = b;
  Q.row(m.rate_index) = b.transpose();
  Q *= m.rate_noise;
  for (int k = 0; k < n; ++k) Q(k, k) += m.drift_rate[static_cast<size_t>(k)] * dt;
  const Eigen::MatrixXd want = F * P0 * F.transpose() + Q;
  EXPECT_LT((used(m, P) - want).norm(), 1e-12 * want.norm());
  // The links grew by rate * dt in proportion to their lengths; nothing else moved.
  for (int i = 0; i < kNumParams; ++i)
    EXPECT_NEAR(x[i] - s.geometry[i], is_length(i) ? 2e-4 * dt * s.geometry[i] / 244.0 : 0.0, 1e-13) << param_name(i);  // ulp(244) ~ 3e-14
  EXPECT_DOUBLE_EQ(rate, 2e-4);
}

TEST(DriftFilter, UpdatesEqualTheInformationFormWithoutProcessNoise) {
  MonitorSettings s;
  s.thermal_tau_s = std::numeric_limits<double>::infinity();
  const MonitorModel m = make_monitor_model(s);
  ASSERT_EQ(m.n_state, m.n_free);
  MonitorData d = make_monitor_data(m);
  testing::CircleStream cs;
  cs.bits = 0;  // exact readings: the estimate stays at the truth
  const int n = m.n_free;
  Eigen::MatrixXd info = Eigen::MatrixXd::Zero(n, n);
  for (int k = 0; k < n; ++k) info(k, k) = 1.0 / m.prior_variance[static_cast<size_t>(k)];
  for (int j = 0; j < 300; ++j) {
    const double t = 0.013 * j;
    const Eigen::Vector3d th = cs.readings(s.geometry, t);
    double r = 0.0;
    ParamRow g;
    ASSERT_TRUE(ml_residual_and_gradient(s.geometry, th, r, g));
    Eigen::VectorXd h(n);
    for (int k = 0; k < n; ++k) h[k] = g[m.free_index[static_cast<size_t>(k)]] / m.scale[static_cast<size_t>(k)];
    info += h * h.transpose() / (m.sigma_rad * m.sigma_rad);
    filter_update(m, d, t, th, Eigen::Vector3d::Zero());
  }
  const Eigen::MatrixXd want = info.inverse();
  const Eigen::VectorXd scale = want.diagonal().cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd diff = scale.asDiagonal() * (used(m, d.P) - want) * scale.asDiagonal();
  EXPECT_LT(diff.norm(), 1e-6);
  for (int i = 0; i < kNumParams; ++i) EXPECT_NEAR(d.estimate[i], s.geometry[i], 1e-9);
}

TEST(DriftFilter, InnovationIsTheResidualOverItsPredictedSpread) {
  const MonitorModel m = make_monitor_model(MonitorSettings{});
  MonitorData d = make_monitor_data(m);
  Geometry truth = m.settings.geometry;
  truth[kLa1] += 0.004;
  testing::CircleStream cs;
  const Eigen::Vector3d th = cs.readings(truth, 0.8);
  double z = 0.0;
  ParamRow dz;
  ASSERT_TRUE(filter_innovation(m, d, 0.8, th, Eigen::Vector3d::Zero(), z, dz));
  double r = 0.0;
  ParamRow g;
  ASSERT_TRUE(ml_residual_and_gradient(d.estimate, th, r, g));
  double hPh = 0.0;  // prior covariance is diagonal
  for (int k = 0; k < m.n_free; ++k) {
    const double h = g[m.free_index[static_cast<size_t>(k)]] / m.scale[static_cast<size_t>(k)];
    hPh += h * h * m.prior_variance[static_cast<size_t>(k)];
  }
  const double s = m.sigma_rad * m.sigma_rad + hPh;
  EXPECT_NEAR(z, r / std::sqrt(s), 1e-12);
  EXPECT_LT((dz - g / std::sqrt(s)).norm(), 1e-9 * g.norm() / std::sqrt(s));
  // The filter's share of z's unit spread: sqrt(h P h' / s).
  double z_filter = -1.0;
  ASSERT_TRUE(filter_innovation(m, d, 0.8, th, Eigen::Vector3d::Zero(), z, dz, 0.0, nullptr, &z_filter));
  EXPECT_NEAR(z_filter, std::sqrt(hPh / s), 1e-12);
  d.P.setZero();  // a filter that knows the robot exactly shares no error
  ASSERT_TRUE(filter_innovation(m, d, 0.8, th, Eigen::Vector3d::Zero(), z, dz, 0.0, nullptr, &z_filter));
  EXPECT_EQ(z_filter, 0.0);
}

}  // namespace
}  // namespace gpm::calib::monitor
