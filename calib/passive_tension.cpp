// Axial force of a passive link (calib/passive_tension.hpp).
#include "calib/passive_tension.hpp"

#include <cmath>

namespace gpm::calib {

double friction_sign(const TransmissionLoad& load, double omega) {
  const double v = load.friction_speed_rad_s;
  return v > 0.0 ? std::tanh(omega / v) : (omega > 0.0 ? 1.0 : (omega < 0.0 ? -1.0 : 0.0));
}

double transmitted_torque(const TransmissionLoad& load, int i, double tau, double omega, double alpha) {
  const auto k = static_cast<std::size_t>(i);
  const double sign = friction_sign(load, omega);
  return tau - load.coulomb_Nm[k] * sign - load.viscous_Nm_s[k] * omega - load.inertia_kg_m2[k] * alpha;
}

double mesh_torque(const TransmissionLoad& load, int i, double tau, double omega, double alpha) {
  const auto k = static_cast<std::size_t>(i);
  const double sign = friction_sign(load, omega);
  return tau - load.coulomb_Nm[k] * sign - load.viscous_Nm_s[k] * omega - load.rotor_inertia_kg_m2[k] * alpha;
}

std::vector<Eigen::Vector3d> mesh_torques(const TransmissionLoad& load, const std::vector<Eigen::Vector3d>& omega,
                                          const std::vector<Eigen::Vector3d>& tau,
                                          const std::vector<Eigen::Vector3d>& alpha) {
  std::vector<Eigen::Vector3d> mesh(omega.size());
  for (std::size_t j = 0; j < omega.size(); ++j)
    for (int i = 0; i < 3; ++i)
      mesh[j][i] = mesh_torque(load, i, tau[j][i], omega[j][i], alpha.empty() ? 0.0 : alpha[j][i]);
  return mesh;
}

double passive_link_tension(const Geometry& g, int i, double theta_a, double theta_b, double tau_t) {
  return -tau_t / (1e-3 * g.la_(i) * std::sin(theta_b - theta_a));
}

double reading_per_passive_length(const Geometry& g, int i, double theta_a, double theta_b) {
  return 1.0 / (g.la_(i) * std::sin(theta_b - theta_a));
}

}  // namespace gpm::calib
