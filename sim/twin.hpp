// The digital twin: the MuJoCo closed chain built from the *actual*
// parameters, three servo drives and three absolute encoders.
// MuJoCo-style split: TwinModel is constant (mjModel, actual robot, drive and
// encoder settings, object ids); TwinState is mutable (mjData, drive states,
// noise source, joint commands, last sensed values).
//
// Use (render/ and hw/ call exactly this):
//   TwinModel model(actual_robot, config);            // compiles the MJCF
//   TwinState state(model, seed);                      // at home, holding position
//   twin_command(state, readings_cmd, readings_rate);  // drive commands (reading frame)
//   twin_step(model, state);                           // one physics step (servo at its rate)
//   state.last.readings / .ee_mm / .torque / .violation_m / .theta_a
#pragma once

#include <array>
#include <string>

#include <Eigen/Core>

#include "models/mjcf.hpp"
#include "models/robot.hpp"
#include "sim/drive_train_step.hpp"
#include "sim/effects.hpp"
#include "sim/encoder_model.hpp"
#include "sim/mujoco_util.hpp"
#include "sim/rotor_friction.hpp"
#include "sim/events.hpp"
#include "sim/servo_drive.hpp"

namespace gpm::sim {

// Settings of a twin besides the actual geometry.
struct TwinConfig {
  MjcfOptions mjcf;                 // masses, damping, armature, timestep, constraint stiffness
                                    // (mjcf.effects is replaced by effects.mjcf)
  double servo_rate_hz = 2000.0;    // drive loop rate; a whole multiple of timesteps
  std::array<ServoDrive, 3> drives; // per joint; period_s is set from servo_rate_hz
  EncoderModel encoder;
  Effects effects;                  // physical effects, all off by default
  std::vector<GeometryEvent> events;  // changes of the actual mechanism during the run (sim/events.hpp)
};

// Constant part of the twin.
class TwinModel {
 public:
  // Builds and compiles the MJCF of actual (assembled at actual.home). Throws
  // InputError for parameters that cannot assemble, a servo rate that is not
  // a whole number of timesteps or a transmission too stiff for the timestep;
  // SimError if MuJoCo rejects the model.
  TwinModel(const Robot& actual, const TwinConfig& config);

  const mjModel* mj() const { return model_.get(); }
  const Robot& actual() const { return actual_; }
  const TwinConfig& config() const { return config_; }
  // The MJCF text the model was compiled from (saved as model.xml).
  const std::string& xml() const { return xml_; }
  // Physics steps per drive loop period.
  int steps_per_tick() const { return steps_per_tick_; }
  double timestep_s() const { return mj()->opt.timestep; }

  // joint_a (link) and, with compliance, joint_m (motor); without compliance
  // qpos_m == qpos_a and dof_m == dof_a.
  std::array<int, 3> qpos_a{}, qpos_b{}, dof_a{}, qpos_m{}, dof_m{}, actuator{}, site_tip{};
  std::array<int, 3> site_side{-1, -1, -1};  // side_b{i} across the tip (clearance, chains 2 and 3), -1 if none
  std::array<int, 3> site_pin{-1, -1, -1};   // hub site where chain i closes: pin_b{i} with hub pin offsets, else ee
  std::array<bool, 3> compliant{};
  int site_ee = -1;
  // Bodies and constraints whose placement a thermal edit changes.
  std::array<int, 3> body_base{}, body_elbow{}, eq_close{};  // eq_close[0] = -1 (chain 1 carries the hub)
  std::array<int, 3> body_rotor{};  // rotor_a{i} with compliance (at A_i too), else -1
  int body_ee = -1;
  // Distance the hub may keep from site tip_b{i} (chains 2 and 3 closed by
  // their clearance tendon: 2c; 0 where a connect closes the loop).
  std::array<double, 3> hub_play_m{};
  // Friction of each drive whose rotor is a tree of its own (compliant
  // transmission), solved by twin_step in closed form (sim/rotor_friction.hpp;
  // the compiled model's frictionloss of joint_m is 0); dof -1 where MuJoCo's
  // frictionloss row acts (a rigid drive: joint_a in the closed chain).
  std::array<RotorFriction, 3> rotor_friction{};
  DriveTrainModel drive_train;  // nonlinear drive trains (sim/drive_train_step.hpp)

  // Largest stable transmission stiffness at a timestep: omega dt <= this.
  static constexpr double kMaxOmegaDt = 1.5;
  // Largest velocity loop gain kv T / armature on a rotor behind a compliant transmission.
  static constexpr double kMaxRotorLoopGain = 1.0;

 private:
  Robot actual_;
  TwinConfig config_;
  std::string xml_;
  ModelPtr model_;
  int steps_per_tick_ = 1;
};

// What the twin sensed at the start of its last step (all at one instant).
struct TwinSnapshot {
  double time_s = 0.0;
  Eigen::Vector3d theta_a = Eigen::Vector3d::Zero();   // true active (link) angles (rad, unwrapped)
  Eigen::Vector3d theta_motor = Eigen::Vector3d::Zero();  // motor angles (rad; = theta_a when rigid)
  Eigen::Vector3d motor_velocity = Eigen::Vector3d::Zero();  // rad/s (servo velocity feedback)
  Eigen::Vector3d theta_b = Eigen::Vector3d::Zero();   // true passive angles from +X (rad)
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // active joint speeds (rad/s)
  Eigen::Vector3d readings = Eigen::Vector3d::Zero();  // encoder readings (rad, [0, 2 pi)), per drive loop
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();    // drive torques applied (N m)
  Eigen::Vector2d ee_mm = Eigen::Vector2d::Zero();     // true end-effector (site ee), mm
  double violation_m = 0.0;  // largest loop-closure gap |tip_b2 - ee|, |tip_b3 - ee| beyond the clearance (m)
  double growth = 0.0;       // thermal: relative length growth in effect (0 without thermal)
  double growth_base = 0.0;  // thermal: relative growth of the base plate in effect (= growth unless it has its own law)
};

// Mutable part of the twin.
struct TwinState {
  // Data at qpos0 (assembled at home), every drive holding its current reading.
  TwinState(const TwinModel& model, unsigned long long seed);

  DataPtr data;
  // With thermal growth or events: this state's own copy of the model, whose
  // geometry follows the actual mechanism as it warms and changes.
  ModelPtr thermal_model;
  std::array<ServoState, 3> servo{};
  EncoderNoise noise;
  Geometry geometry;  // the actual geometry in effect now (the encoders read against its offsets)
  Eigen::Vector3d command_position = Eigen::Vector3d::Zero();  // readings (rad)
  Eigen::Vector3d command_velocity = Eigen::Vector3d::Zero();  // rad/s
  long long steps = 0;
  DriveTrainState drive_train;  // hysteresis slip, transmitted torque
  TwinSnapshot last;
};

// Sets the drives' position commands (in the reading frame, rad) and velocity
// feed-forward (rad/s); they take effect at the next drive loop update.
void twin_command(TwinState& state, const Eigen::Vector3d& position, const Eigen::Vector3d& velocity);

// Advances one physics step: kinematics at the current state, then (on drive
// loop ticks) encoders and servo torques, then integration. Throws SimError
// if the simulation diverges.
void twin_step(const TwinModel& model, TwinState& state);

// Recomputes state.last from the current mjData without stepping (encoders
// are read, drawing noise).
void twin_sense(const TwinModel& model, TwinState& state);

// The mjModel this state steps (its thermal copy, or the shared model).
inline const mjModel* state_model(const TwinModel& model, const TwinState& state) {
  return state.thermal_model ? state.thermal_model.get() : model.mj();
}

// Sets the state's own model copy to geometry g: base bodies, elbow and tip
// offsets, tip sites and connect anchors (and state.geometry, whose offsets
// the encoders use). Never followed by mj_setConst (it would recompute the
// anchors and hide the edit from the loop).
void apply_geometry(const TwinModel& model, TwinState& state, const Geometry& g);

// apply_geometry of the actual geometry grown by `growth`, links and base alike
// (sim/effects.hpp thermal_geometry), recorded in state.last.growth and .growth_base.
void apply_thermal_growth(const TwinModel& model, TwinState& state, double growth);

// The actual geometry at time t: the events so far, then thermal growth.
Geometry geometry_at_time(const TwinModel& model, double t_s);

// The MJCF options of a config with its effects (config.mjcf, effects = config.effects.mjcf).
MjcfOptions mjcf_with_effects(const TwinConfig& config);

// Throws InputError (key effects.transmission_compliance_rad_per_Nm) if a
// compliant transmission of config cannot be integrated: explicit
// integration holds omega dt <= TwinModel::kMaxOmegaDt (docs/ARCHITECTURE.md measured
// instability near 2; omega from transmission_omega), and the drive's
// velocity loop, which then acts on the rotor alone, needs
// kv / rate_hz / armature <= TwinModel::kMaxRotorLoopGain. A drive train
// (sim/drive_train_step.hpp check_drive_train) is checked first.
void check_transmission(const Robot& actual, const TwinConfig& config);

// Loop-closure gap (m) of the current mjData kinematics (after mj_forward or
// mj_step1): the largest distance between tip_b2 / tip_b3 and their hub site
// (site_pin: ee, or pin_b{i} with hub pin offsets) beyond the play the
// clearance allows there (hub_play_m; 0 within it).
double constraint_violation_m(const TwinModel& model, const mjData* d);

}  // namespace gpm::sim
