// MJCF (MuJoCo XML) of a 3-RRR planar manipulator from any parameter set.
// Pure text generation: no MuJoCo dependency (sim/ loads the text).
//
// Layout (names are a contract for sim/, render/ and hw/):
//   body link_a{i}  hinge joint_a{i} about +Z at A_i   (active link, motor)
//   body link_b{i}  hinge joint_b{i} at the elbow B_i  (passive link)
//   body ee         welded to the tip of link_b1, site ee at the end-effector O
//   site tip_b{i}   at the free end of link_b{i} (tip_b1 coincides with ee)
//   equality close_b2, close_b3: <connect> tip of link_b2 / link_b3 to ee
//     (absent for a chain with clearance, see below)
//   actuator motor_a{i}: torque motor on joint_a{i} (gear 1, N m)
// Physical effects (MjcfEffects, all off by default; off = the layout above,
// byte for byte):
//   compliance: body rotor_a{i} at A_i (a tree of its own) with hinge
//     joint_m{i} (the rotor armature, damping, friction; the actuator), and
//     link_a{i} on its absolute hinge joint_a{i} as without compliance; a
//     fixed tendon twist_a{i} = joint_m{i} - joint_a{i} of stiffness
//     1/compliance joins them. Both joints have ref = springref = home
//     angle: qpos(joint_m) = motor angle, qpos(joint_a) = link angle,
//     twist = motor - link (docs/ARCHITECTURE.md: springref must be given;
//     it defaults to 0, not to ref).
//   clearance: each passive link's length |O - B_i| gives by up to +-2c
//     (the elbow and hub pins' radial play c each, summed). Chain 1 (it
//     carries ee): a slide clear_b1x in link_b1 after joint_b1, along the
//     link, range +-2c. Chains 2 and 3: no connect close_b{i}; a spatial
//     tendon clear_b{i} from site tip_b{i} to site ee limited to length 2c
//     closes the loop (the hub anywhere within 2c of the link's tip: the
//     two pins' discs summed); site side_b{i} 0.1 m across the tip, tendon
//     side_b{i} from it to ee and the tendon equality hold_b{i} keep the hub
//     on the link's line (the play is axial, as chain 1's slide). No extra
//     bodies (mjcf.cpp).
//   friction: frictionloss (Coulomb, N m) and extra damping on the actuated joint.
//   hub pin offsets: body ee gets hinge hub_r and sites pin_b2, pin_b3 where
//     chains 2 and 3 close (models/hub_pins.hpp).
// Bodies are laid out already assembled at the actual inverse kinematics of
// robot.home (paper eq. 29-31), so <connect>, which takes its second anchor at
// qpos0, closes the loops exactly (docs/ARCHITECTURE.md, MuJoCo facts). Joint qpos are
// absolute for joint_a (qpos = theta_a) and relative for joint_b
// (qpos = theta_b - theta_a). Metres inside MuJoCo; millimetres outside.
#pragma once

#include <array>
#include <string>

#include "models/robot.hpp"

namespace gpm {

// The one place where millimetres become metres for MuJoCo.
inline constexpr double kMetresPerMm = 1e-3;

// MuJoCo's default time constant of a frictionloss row (solreffriction), s.
inline constexpr double kMujocoFrictionTimeconst = 0.02;

// Effects built into the MuJoCo model (per chain; 0 = off).
struct MjcfEffects {
  std::array<double, 3> compliance_rad_per_Nm{};  // transmission, motor to link
  std::array<double, 3> clearance_m{};            // radial, elbow B_i and hub joint of chain i (each)
  std::array<double, 3> coulomb_Nm{};             // frictionloss at the actuated joint
  std::array<double, 3> viscous_Nm_s{};           // damping added to active_damping
  double rotor_mass_kg = 0.05;                    // rotor body (compliance only; inertia is the armature)
  // Time constant (s) of the drives' friction, MuJoCo's soft frictionloss
  // (solreffriction): below F a drive creeps, a coasting rotor slows as
  // exp(-t / ~T/2). 0 (the twin's): two physics steps, the stiffest MuJoCo
  // allows (a rotor near hard Coulomb); MuJoCo's default, 0.02, is written
  // as no attribute.
  double friction_timeconst_s = 0.0;
  double clearance_stiffness_N_per_m = 200.0;     // soft centring spring of each loose pin
  double clearance_damping_N_s_per_m = 2.0;       // damping of each loose pin (two pins in series per link)
  // Limit time constant: 2 steps at 0.25 ms (MuJoCo raises it to 2 timesteps
  // at longer steps; why not longer: docs/ARCHITECTURE.md, clearance).
  double clearance_solref_s = 0.0005;
  // Limit impedance, as the loop constraints': MuJoCo's default soft limits
  // give way on light bodies (docs/ARCHITECTURE.md, clearance).
  double clearance_solimp = 0.9999;
  // Hub pin offsets p_i (m, hub frame): the distal pin of passive link i sits
  // at the hub centre + R(phi) p_i (models/hub_pins.hpp); zero = one common pin.
  std::array<std::array<double, 2>, 3> hub_pin_m{};

  bool compliant() const;
  bool loose() const;
  // True if a hub pin offset is non-zero (models/hub_pins.cpp).
  bool pinned_hub() const;
};

// Mass, drive and solver properties of the MJCF (GPM2002-sized defaults; the
// reasoning behind each number is in mjcf.cpp).
struct MjcfOptions {
  double timestep_s = 0.0005;          // physics step; servo loops run at a multiple
  double active_link_mass_kg = 0.40;   // aluminium bar 244 x 40 x 15 mm
  double passive_link_mass_kg = 0.25;  // aluminium bar 244 x 30 x 12 mm
  double ee_mass_kg = 0.10;            // end-effector hub and tool
  double link_radius_m = 0.012;        // capsule radius (visual only; contacts are off)
  double active_damping = 0.05;        // N m s/rad, gearbox viscous friction (output side)
  double passive_damping = 0.002;      // N m s/rad, ball-bearing elbow and end-effector joints
  double armature_kg_m2 = 0.0026;      // reflected rotor inertia, 0.26e-4 kg m^2 x 10^2
  double solref_timeconst_s = 0.001;   // equality constraint time constant (>= 2 timesteps)
  double solref_dampratio = 1.0;
  double solimp_dmin = 0.9999;         // equality constraint impedance at zero violation
  double solimp_dmax = 0.9999;         // ... and beyond solimp_width_m
  double solimp_width_m = 0.001;
  MjcfEffects effects;                 // physical effects, all off by default
};

// Rotational rate (rad/s) of chain i's transmission spring: omega^2 = k (1/Ia
// + 1/Il) with Ia the armature and Il the active link's inertia about its axis
// (the passive chain only adds inertia, so this is an upper bound); 0 if rigid.
double transmission_omega(const MjcfOptions& options, int chain, double la_m);

// MJCF text of the mechanism with the given (actual) parameters, assembled at
// robot.home. Throws InputError if the parameters cannot assemble there.
std::string mjcf_from_robot(const Robot& actual, const MjcfOptions& options = {});

}  // namespace gpm
