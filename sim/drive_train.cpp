// Drive-train laws (the mathematics is in sim/drive_train.hpp).
#include "sim/drive_train.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sim/effects.hpp"

namespace gpm::sim {

bool DriveChain::mesh_on() const {
  return backlash_rad != 0.0 || stiffness_Nm_per_rad[0] != 0.0 || hysteresis_rad != 0.0 || te_joint_rad != 0.0 ||
         te_motor_rad != 0.0 || stiction_excess_Nm != 0.0 || load_friction != 0.0;
}

bool DriveChain::motor_on() const { return torque_constant_delta != 0.0 || cogging_Nm != 0.0; }

bool DriveTrain::any() const {
  return std::any_of(chain.begin(), chain.end(), [](const DriveChain& c) { return c.mesh_on() || c.motor_on(); });
}

// Band edges: e1 = T1/K1, e2 = e1 + (T2 - T1)/K2 (infinite when T is 0, a single band).
namespace {
double edge1(const DriveChain& c) {
  return c.band_Nm[0] > 0.0 ? c.band_Nm[0] / c.stiffness_Nm_per_rad[0] : INFINITY;
}
double edge2(const DriveChain& c) {
  return c.band_Nm[1] > 0.0 ? edge1(c) + (c.band_Nm[1] - c.band_Nm[0]) / c.stiffness_Nm_per_rad[1] : INFINITY;
}
}  // namespace

double band_torque(const DriveChain& c, double e) {
  const auto& K = c.stiffness_Nm_per_rad;
  const double a = std::abs(e), e1 = edge1(c), e2 = edge2(c);
  double tau;
  if (a <= e1) tau = K[0] * a;
  else if (a <= e2) tau = c.band_Nm[0] + K[1] * (a - e1);
  else tau = c.band_Nm[1] + K[2] * (a - e2);
  return std::copysign(tau, e);
}

double band_twist(const DriveChain& c, double tau) {
  const auto& K = c.stiffness_Nm_per_rad;
  const auto& T = c.band_Nm;
  const double a = std::abs(tau);
  double e;
  if (!(T[0] > 0.0) || a <= T[0]) e = a / K[0];
  else if (!(T[1] > 0.0) || a <= T[1]) e = edge1(c) + (a - T[0]) / K[1];
  else e = edge2(c) + (a - T[1]) / K[2];
  return std::copysign(e, tau);
}

double dead_band(double delta, double b) {
  const double h = 0.5 * b;
  if (delta > h) return delta - h;
  if (delta < -h) return delta + h;
  return 0.0;
}

double transmission_error(const DriveChain& c, double theta_m, double gear_ratio, int order) {
  double te = 0.0;
  if (c.te_joint_rad != 0.0) te += c.te_joint_rad * std::sin(theta_m + c.te_joint_phase_rad);
  if (c.te_motor_rad != 0.0) te += c.te_motor_rad * std::sin(order * gear_ratio * theta_m + c.te_motor_phase_rad);
  return te;
}

double transmission_torque(const DriveChain& c, double delta, double& s) {
  const double e = c.backlash_rad > 0.0 ? dead_band(delta, c.backlash_rad) : delta;
  if (c.backlash_rad > 0.0 && e == 0.0) {  // in the gap: no flank touches
    s = 0.0;
    return 0.0;
  }
  double tau = band_torque(c, e);
  if (c.hysteresis_rad > 0.0) {
    const double h = 0.5 * c.hysteresis_rad;
    s = std::clamp(s, e - h, e + h);
    tau += c.stiffness_Nm_per_rad[0] * (e - s);
  }
  if (c.backlash_rad > 0.0 && tau * e < 0.0) return 0.0;  // a flank pushes, never pulls
  return tau;
}

double friction_bound(const DriveChain& c, double coulomb_Nm, double omega_m, double tau_t) {
  double F = coulomb_Nm + c.load_friction * std::abs(tau_t);
  if (c.stiction_excess_Nm > 0.0 && c.stribeck_speed_rad_s > 0.0) {
    const double r = omega_m / c.stribeck_speed_rad_s;
    F += c.stiction_excess_Nm * std::exp(-r * r);
  }
  return F;
}

double applied_torque(const DriveChain& c, double tau_reported, double theta_m, double gear_ratio, int periods) {
  double tau = (1.0 + c.torque_constant_delta) * tau_reported;
  if (c.cogging_Nm != 0.0) tau += c.cogging_Nm * std::sin(periods * gear_ratio * theta_m + c.cogging_phase_rad);
  return tau;
}

double stiffest(const DriveChain& c) {
  const auto& K = c.stiffness_Nm_per_rad;
  return std::max({K[0], K[1], K[2]}) + (c.hysteresis_rad > 0.0 ? K[0] : 0.0);
}

namespace {
double uniform(Rng& rng, const double (&r)[2]) { return rng.uniform(r[0], r[1]); }
double log_uniform(Rng& rng, const double (&r)[2]) { return std::exp(rng.uniform(std::log(r[0]), std::log(r[1]))); }
}  // namespace

void draw_drive_train(Rng& rng, Effects& e) {
  const PlausibleDriveTrain& p = kPlausible;
  const double two_pi = 2.0 * std::numbers::pi;
  for (DriveChain& c : e.drive.chain) {
    c.backlash_rad = log_uniform(rng, p.backlash_rad);
    auto& K = c.stiffness_Nm_per_rad;
    K[0] = uniform(rng, p.k1_Nm_per_rad);
    K[1] = K[0] * uniform(rng, p.k_step);
    K[2] = K[1] * uniform(rng, p.k_step);
    c.band_Nm = {uniform(rng, p.t1_Nm), uniform(rng, p.t2_Nm)};
    c.hysteresis_rad = uniform(rng, p.hysteresis_rad);
    c.te_joint_rad = uniform(rng, p.te_joint_rad);
    c.te_joint_phase_rad = rng.uniform(0.0, two_pi);
    c.te_motor_rad = uniform(rng, p.te_motor_rad);
    c.te_motor_phase_rad = rng.uniform(0.0, two_pi);
    c.stiction_excess_Nm = uniform(rng, p.stiction_excess_Nm);
    c.stribeck_speed_rad_s = log_uniform(rng, p.stribeck_speed_rad_s);
    c.load_friction = uniform(rng, p.load_friction);
    c.torque_constant_delta = uniform(rng, p.torque_constant_delta);
    c.cogging_Nm = uniform(rng, p.cogging_Nm);
    c.cogging_phase_rad = rng.uniform(0.0, two_pi);
  }
}

}  // namespace gpm::sim
