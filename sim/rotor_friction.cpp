#include "sim/rotor_friction.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "sim/mujoco_util.hpp"

namespace gpm::sim {

RotorFriction take_rotor_friction(mjModel* m, int dof, int actuator) {
  const int body = dof >= 0 && dof < m->nv ? m->dof_bodyid[dof] : -1;
  if (body < 0 || m->body_parentid[body] != 0 || m->body_dofnum[body] != 1)
    throw SimError(fmt::format("MuJoCo model: dof {} is not the only dof of a body on the world", dof));
  if (actuator >= 0 &&
      (actuator >= m->nu || m->actuator_trntype[actuator] != mjTRN_JOINT ||
       m->jnt_dofadr[m->actuator_trnid[2 * actuator]] != dof || m->actuator_dyntype[actuator] != mjDYN_NONE ||
       m->actuator_gaintype[actuator] != mjGAIN_FIXED || m->actuator_biastype[actuator] != mjBIAS_NONE))
    throw SimError(fmt::format("MuJoCo model: actuator {} is not a motor on dof {}", actuator, dof));
  const mjtNum* solref = m->dof_solref + mjNREF * dof;
  const mjtNum* solimp = m->dof_solimp + mjNIMP * dof;
  RotorFriction r;
  r.dof = dof;
  r.actuator = actuator;
  r.coulomb_Nm = m->dof_frictionloss[dof];
  // Impedance at zero violation (a friction row has none): dmin, or the
  // midpoint where MuJoCo treats the sigmoid as flat.
  const double d = solimp[0] == solimp[1] || solimp[2] <= mjMINVAL ? 0.5 * (solimp[0] + solimp[1]) : solimp[0];
  r.regulariser = std::max(mjMINVAL, (1.0 - d) / d * m->dof_invweight0[dof]);
  if (solref[0] > 0.0) {
    double timeconst = solref[0];
    if (!(m->opt.disableflags & mjDSBL_REFSAFE)) timeconst = std::max(timeconst, 2.0 * m->opt.timestep);
    r.damping_ref = 2.0 / (solimp[1] * timeconst);
  } else {
    r.damping_ref = -solref[1] / solimp[1];
  }
  m->dof_frictionloss[dof] = 0.0;
  return r;
}

namespace {

// f: passive, actuator (as mj_fwdActuation will compute it in mj_step2) less bias torque on r.dof.
double rotor_torque(const mjModel* m, const mjData* d, const RotorFriction& r) {
  const int v = r.dof;
  double f = d->qfrc_passive[v] - d->qfrc_bias[v];
  if (r.actuator >= 0) {
    const int a = r.actuator;
    double u = d->ctrl[a];
    if (m->actuator_ctrllimited[a]) u = std::clamp(u, m->actuator_ctrlrange[2 * a], m->actuator_ctrlrange[2 * a + 1]);
    double force = m->actuator_gainprm[mjNGAIN * a] * u;
    if (m->actuator_forcelimited[a])
      force = std::clamp(force, m->actuator_forcerange[2 * a], m->actuator_forcerange[2 * a + 1]);
    f += m->actuator_gear[6 * a] * force;
  }
  return f;
}

// The clamp of the header's closed form for the total torque f and bound F.
double clamp_friction(const mjModel* m, const mjData* d, const RotorFriction& r, double f, double F) {
  const double inertia = d->qM[m->dof_Madr[r.dof]];
  const double a0 = f / inertia;
  const double aref = -r.damping_ref * d->qvel[r.dof];
  return std::clamp(-(a0 - aref) / (1.0 / inertia + r.regulariser), -F, F);
}

}  // namespace

double rotor_friction_torque(const mjModel* m, const mjData* d, const RotorFriction& r) {
  return clamp_friction(m, d, r, rotor_torque(m, d, r), r.coulomb_Nm);
}

double rotor_friction_torque(const mjModel* m, const mjData* d, const RotorFriction& r, double applied_Nm,
                             double coulomb_Nm) {
  return clamp_friction(m, d, r, rotor_torque(m, d, r) + applied_Nm, coulomb_Nm);
}

}  // namespace gpm::sim
