// Coulomb friction of a drive rotor that is a one-dof tree of its own (the
// compliant transmission, models/mjcf.cpp): MuJoCo's frictionloss row on that
// dof solved in closed form instead of by the constraint solver.
//
// The rotor's dof has a mass-matrix block of its own (I, armature included)
// and no other constraint row touches it, so its frictionloss row decouples
// from the rest of the constraint problem and its solution is one clamp:
//   a0     = f / I                      unconstrained acceleration (f: passive,
//                                       actuator and applied torque, less bias)
//   aref   = -b omega                   reference acceleration, b = 2 / (dmax T)
//                                       (solref T, clamped to 2 h; solimp dmax)
//   R      = (1 - d) / d  w0            regulariser: impedance d = dmin at zero
//                                       violation, w0 = dof_invweight0
//   f_fric = clamp(-(a0 - aref) / (1/I + R), -F, F)
// MuJoCo's soft friction (a rotor under a steady torque below F creeps
// rather than sticks; the creep speed and the build-up of the friction with
// speed follow from R and b) is kept exactly: tests/sim/test_rotor_friction.cpp
// steps both side by side. What it saves is the constraint row: with three
// drives the solver's rows drop from 8 to 5 (bench/sim_README.md).
#pragma once

#include <mujoco/mujoco.h>

namespace gpm::sim {

// The frictionloss of one rotor dof, taken over from the model.
struct RotorFriction {
  int dof = -1;             // the rotor's dof (a hinge whose body is a child of the world)
  int actuator = -1;        // the motor on that dof (its torque enters f), -1 if none
  double coulomb_Nm = 0.0;  // F: the dof's frictionloss
  double regulariser = 0.0; // R (1 / (kg m^2), as 1 / I)
  double damping_ref = 0.0; // b (1/s)
};

// Reads dof's frictionloss and its solver parameters from m and sets the
// dof's frictionloss in m to 0 (the caller then applies rotor_friction_torque
// every step). Throws SimError unless dof is the only dof of a body whose
// parent is the world and actuator (if >= 0) is a plain motor on that dof.
RotorFriction take_rotor_friction(mjModel* m, int dof, int actuator);

// Friction torque (N m) to set as qfrc_applied[r.dof] between mj_step1 and
// mj_step2, after the actuator's ctrl is set for this step (qM, qfrc_passive
// and qfrc_bias of mj_step1; qfrc_applied[r.dof] is otherwise 0).
double rotor_friction_torque(const mjModel* m, const mjData* d, const RotorFriction& r);

// The same with a further torque applied_Nm on the rotor (the caller's own
// qfrc_applied besides the friction) and the bound coulomb_Nm instead of
// r.coulomb_Nm (a bound that changes with speed and load, sim/drive_train.hpp).
double rotor_friction_torque(const mjModel* m, const mjData* d, const RotorFriction& r, double applied_Nm,
                             double coulomb_Nm);

}  // namespace gpm::sim
