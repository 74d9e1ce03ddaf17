// The monitor's drift tracker: an extended Kalman filter over the estimated
// parameters u (scaled, MonitorModel::scale) and the common thermal growth
// rate rho of the links.
//
// Process model over dt (constant-rate growth plus random walks):
//   u_k(t + dt) = u_k(t) + v_k rho dt + w_k,     rho(t + dt) = rho(t) + w_rho,
// with v the growth direction (L_i / mean L for link lengths, 0 otherwise),
// w_k independent random walks of variance drift_rate_k dt and w_rho a random
// walk of variance rate_noise dt (integrated into u: the discrete process
// noise of a white rate derivative, [dt^3/3 v v', dt^2/2 v; dt^2/2 v', dt]).
// With a stated cyclic encoder error the state also holds its coefficients
// a_i, b_i (constant; the readings lose a_i sin theta_i + b_i cos theta_i),
// and with a stated clearance the effective play d_i of each chain
// (constant; the passive length is lb_i + d_i sign(T_i)).
// Measurement: the ML residual of the readings, r(u) = 0 with variance
// sigma^2 (calib/residuals.hpp) at the geometry with each passive length
// shifted by the sample's play (ReadingModel::clearance_mm),
// linearised at the current estimate.
#pragma once

#include "calib/monitor/monitor.hpp"

namespace gpm::calib::monitor {

// Predicted estimate and covariance dt seconds after the filter's state.
// Allocation-free.
void filter_predict(const MonitorModel& model, Geometry& estimate, double& growth_rate,
                    StateMatrix& P, double dt);

// Normalised innovation of readings theta_m taken at t_s against the filter
// predicted to t_s: z = r / sqrt(s), s = sigma^2 + h P h' with h = dr/du.
// Also returns dz/dparams = (dr/dparams) / sqrt(s). False when the readings
// have no ML residual (collinear elbows). Allocation-free.
// tension: the sign of each passive link's axial force for the sample (its
// length is lb_i + d_i tension_i, d_i the estimated effective play).
// r_map (rad) is taken off the residual first (the configuration map,
// config_map.hpp); r_out (optional) receives the residual before it;
// z_filter (optional) the filter's share of z's unit standard deviation,
// sqrt(h P h' / s).
bool filter_innovation(const MonitorModel& model, const FilterWindow& data, double t_s,
                       const Eigen::Vector3d& theta_m, const Eigen::Vector3d& tension, double& z,
                       ParamRow& dz_dparams, double r_map = 0.0, double* r_out = nullptr,
                       double* z_filter = nullptr);

// Kalman update with one sample (predict to t_s, then K = P h' / s,
// u += K (0 - r), P -= K h P). Directions h does not see get no gain.
// Allocation-free.
// r_map as for filter_innovation.
void filter_update(const MonitorModel& model, FilterWindow& data, double t_s,
                   const Eigen::Vector3d& theta_m, const Eigen::Vector3d& tension, double r_map = 0.0);

}  // namespace gpm::calib::monitor
