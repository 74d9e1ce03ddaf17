// The drive train (sim/drive_train.hpp) inside the twin. MuJoCo-style split:
// DriveTrainModel is constant (laws per chain, ids, the rotor friction taken
// over), DriveTrainState is mutable (hysteresis slip, last transmitted torque).
//
// A chain whose mesh is on (backlash, stiffness bands, hysteresis,
// transmission error, stiction/Stribeck or load friction) needs the compliant
// transmission's rotor (models/mjcf.hpp): stiffness bands build it (the MJCF
// spring set to the stiffest band, only for the stability check and
// model.xml); otherwise effects.transmission_compliance_rad_per_Nm must be on
// for that chain, and its linear stiffness 1/c is the one band. The compiled
// twist_a{i} spring is then set to 0 and each step, between mj_step1 and
// mj_step2, the twin applies
//   qfrc_applied[dof_a] = +tau_t                 (the mesh drives the link)
//   qfrc_applied[dof_m] = -tau_t + f_fric        (and holds the rotor back)
// with f_fric the rotor friction in MuJoCo's soft form (sim/rotor_friction.hpp)
// clamped to the bound F(omega_m, tau_t). A chain whose motor is on gets
// ctrl = (1 + delta_k) tau_reported + cogging every step; the servo's torque
// (state.servo[i].torque, state.last.torque) stays the reported one.
#pragma once

#include <array>

#include <mujoco/mujoco.h>

#include "models/robot.hpp"
#include "sim/drive_train.hpp"
#include "sim/rotor_friction.hpp"
#include "sim/servo_drive.hpp"

namespace gpm {
struct MjcfEffects;
}

namespace gpm::sim {

struct Effects;
struct TwinConfig;

// Constant part.
struct DriveTrainModel {
  bool on = false;                     // any chain's mesh or motor
  std::array<bool, 3> mesh{}, motor{};
  std::array<DriveChain, 3> chain{};   // bands resolved (a linear compliance as one band)
  double gear_ratio = 1.0;
  int te_motor_order = 2, cogging_periods = 24;
  std::array<int, 3> qpos_m{}, qpos_a{}, dof_m{}, dof_a{}, actuator{};
  std::array<double, 3> te_home{};     // TE(theta_m0): the mesh is at rest at home
  std::array<double, 3> coulomb_Nm{};  // F_c
  std::array<RotorFriction, 3> friction{};  // regulariser and reference of each mesh chain's rotor
};

// Mutable part.
struct DriveTrainState {
  std::array<double, 3> slip_rad{};  // s of the hysteresis element
  std::array<double, 3> tau_t{};     // last transmitted torque (N m)
};

// The MJCF effects with a rotor on every chain with stiffness bands: its
// compliance set to 1 / stiffest (replacing a given compliance).
void drive_train_rotors(const Effects& fx, MjcfEffects& mjcf);

// Throws InputError (key effects.drive_stiffness_Nm_per_rad or
// effects.transmission_compliance_rad_per_Nm) if a chain's mesh is on without
// a rotor, or its stiffest band fails omega dt <= kMaxOmegaDt.
void check_drive_train(const Robot& actual, const TwinConfig& config, double max_omega_dt);

// Builds the constant part from the compiled model m (ids from the twin),
// zeroes twist_a{i}'s stiffness of each mesh chain and moves that rotor's
// friction from rotor_friction into the drive train (taking it from m if absent).
DriveTrainModel make_drive_train(mjModel* m, const Effects& fx, const std::array<int, 3>& qpos_m,
                                 const std::array<int, 3>& qpos_a, const std::array<int, 3>& dof_m,
                                 const std::array<int, 3>& dof_a, const std::array<int, 3>& actuator,
                                 std::array<RotorFriction, 3>& rotor_friction);

// One step's forces (after mj_step1 and the servo update, before mj_step2):
// ctrl of motor chains, qfrc_applied of mesh chains.
void drive_train_step(const DriveTrainModel& dm, const mjModel* m, mjData* d, const std::array<ServoState, 3>& servo,
                      DriveTrainState& s);

}  // namespace gpm::sim
