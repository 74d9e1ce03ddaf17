// The drive train inside the twin (see sim/drive_train_step.hpp).
#include "sim/drive_train_step.hpp"

#include <cmath>

#include <fmt/format.h>

#include "models/errors.hpp"
#include "models/mjcf.hpp"
#include "sim/effects.hpp"
#include "sim/mujoco_util.hpp"
#include "sim/twin.hpp"

namespace gpm::sim {

void drive_train_rotors(const Effects& fx, MjcfEffects& mjcf) {
  for (size_t k = 0; k < 3; ++k) {
    const DriveChain& c = fx.drive.chain[k];
    if (c.stiffness_Nm_per_rad[0] > 0.0) mjcf.compliance_rad_per_Nm[k] = 1.0 / stiffest(c);
  }
}

void check_drive_train(const Robot& actual, const TwinConfig& config, double max_omega_dt) {
  const MjcfOptions o = mjcf_with_effects(config);  // rotors of stiffness bands included
  for (int i = 0; i < 3; ++i) {
    const size_t k = static_cast<size_t>(i);
    DriveChain c = config.effects.drive.chain[k];
    if (!c.mesh_on()) continue;
    const double compliance = o.effects.compliance_rad_per_Nm[k];
    if (!(compliance > 0.0))
      throw InputError(fmt::format(
          "effects.transmission_compliance_rad_per_Nm: chain {}: the drive train's backlash, hysteresis, "
          "transmission error and friction act between rotor and link: give this chain a compliance > 0 "
          "or effects.drive_stiffness_Nm_per_rad", i + 1));
    if (!(c.stiffness_Nm_per_rad[0] > 0.0)) c.stiffness_Nm_per_rad.fill(1.0 / compliance);
    MjcfOptions stiff = o;
    stiff.effects.compliance_rad_per_Nm[k] = 1.0 / stiffest(c);
    const double omega_dt = transmission_omega(stiff, i, actual.geometry.la_(i) * kMetresPerMm) * o.timestep_s;
    if (omega_dt > max_omega_dt)
      throw InputError(fmt::format(
          "effects.drive_stiffness_Nm_per_rad: chain {}: the stiffest band {:.4g} N m/rad (K1 added with "
          "hysteresis) is too stiff for physics.timestep_s {} (omega dt = {:.3g} > {}); use a timestep of at "
          "most {:.3g} s", i + 1, stiffest(c), o.timestep_s, omega_dt, max_omega_dt,
          o.timestep_s * max_omega_dt / omega_dt));
  }
}

namespace {

// Chain i's constants with the stiffness resolved (a linear compliance as one band).
DriveChain resolved(const DriveChain& c, double compliance) {
  DriveChain r = c;
  if (!(r.stiffness_Nm_per_rad[0] > 0.0)) {
    r.stiffness_Nm_per_rad.fill(1.0 / compliance);
    r.band_Nm = {0.0, 0.0};
  }
  return r;
}

}  // namespace

DriveTrainModel make_drive_train(mjModel* m, const Effects& fx, const std::array<int, 3>& qpos_m,
                                 const std::array<int, 3>& qpos_a, const std::array<int, 3>& dof_m,
                                 const std::array<int, 3>& dof_a, const std::array<int, 3>& actuator,
                                 std::array<RotorFriction, 3>& rotor_friction) {
  DriveTrainModel dm;
  dm.gear_ratio = fx.gear_ratio;
  dm.te_motor_order = fx.drive.te_motor_order;
  dm.cogging_periods = fx.drive.cogging_periods_per_motor_rev;
  dm.qpos_m = qpos_m, dm.qpos_a = qpos_a, dm.dof_m = dof_m, dm.dof_a = dof_a, dm.actuator = actuator;
  for (int i = 0; i < 3; ++i) {
    const size_t k = static_cast<size_t>(i);
    const DriveChain& c = fx.drive.chain[k];
    dm.motor[k] = c.motor_on();
    dm.mesh[k] = c.mesh_on();
    dm.chain[k] = c;
    if (!dm.mesh[k]) continue;
    const int tendon = require_id(m, mjOBJ_TENDON, fmt::format("twist_a{}", i + 1).c_str());
    dm.chain[k] = resolved(c, 1.0 / m->tendon_stiffness[tendon]);
    m->tendon_stiffness[tendon] = 0.0;  // the mesh torque replaces the linear spring
    dm.te_home[k] = transmission_error(c, m->qpos0[qpos_m[i]], dm.gear_ratio, dm.te_motor_order);
    dm.friction[k] = rotor_friction[k].dof >= 0 ? rotor_friction[k] : take_rotor_friction(m, dof_m[i], actuator[i]);
    dm.coulomb_Nm[k] = dm.friction[k].coulomb_Nm;
    rotor_friction[k] = RotorFriction{};  // now solved here, with the mesh torque
  }
  dm.on = fx.drive.any();
  return dm;
}

void drive_train_step(const DriveTrainModel& dm, const mjModel* m, mjData* d, const std::array<ServoState, 3>& servo,
                      DriveTrainState& s) {
  for (size_t k = 0; k < 3; ++k) {
    const DriveChain& c = dm.chain[k];
    const double theta_m = d->qpos[dm.qpos_m[k]];
    if (dm.motor[k])
      d->ctrl[dm.actuator[k]] = applied_torque(c, servo[k].torque, theta_m, dm.gear_ratio, dm.cogging_periods);
    if (!dm.mesh[k]) continue;
    const double theta_a = d->qpos[dm.qpos_a[k]];
    const double te = transmission_error(c, theta_m, dm.gear_ratio, dm.te_motor_order) - dm.te_home[k];
    const double tau_t = transmission_torque(c, theta_m - theta_a - te, s.slip_rad[k]);
    s.tau_t[k] = tau_t;
    d->qfrc_applied[dm.dof_a[k]] = tau_t;
    const double F = friction_bound(c, dm.coulomb_Nm[k], d->qvel[dm.dof_m[k]], tau_t);
    d->qfrc_applied[dm.dof_m[k]] = -tau_t + (F > 0.0 ? rotor_friction_torque(m, d, dm.friction[k], -tau_t, F) : 0.0);
  }
}

}  // namespace gpm::sim
