#include "sim/twin.hpp"

#include <cmath>

#include <fmt/format.h>

#include "models/errors.hpp"

namespace gpm::sim {
namespace {

std::string name(const char* stem, int i) { return fmt::format("{}{}", stem, i + 1); }

Eigen::Vector3d site_pos(const mjData* d, int site) {
  return {d->site_xpos[3 * site], d->site_xpos[3 * site + 1], d->site_xpos[3 * site + 2]};
}

// Encoders and kinematic quantities at the current mjData (kinematics computed).
void sense_kinematics(const TwinModel& model, const mjData* d, TwinSnapshot& s) {
  s.time_s = d->time;
  for (int i = 0; i < 3; ++i) {
    // Absolute angles (with compliance, joint_m is the rotor and joint_a the link).
    s.theta_motor[i] = d->qpos[model.qpos_m[i]];
    s.motor_velocity[i] = d->qvel[model.dof_m[i]];
    s.theta_a[i] = d->qpos[model.qpos_a[i]];
    s.velocity[i] = d->qvel[model.dof_a[i]];
    s.theta_b[i] = s.theta_a[i] + d->qpos[model.qpos_b[i]];
  }
  const Eigen::Vector3d ee = site_pos(d, model.site_ee);
  s.ee_mm = Eigen::Vector2d(ee.x(), ee.y()) / kMetresPerMm;
  s.violation_m = constraint_violation_m(model, d);
}

// Readings follow the motors. The latch of encoder i is dt_i = skew_i +
// jitter earlier than the snapshot instant (angle extrapolated with the motor
// speed: theta - dt_i w), and the encoder error e_i(theta - dth_i) of
// sim/encoder_error.hpp (per motor revolution) is added before noise and
// quantisation to 2^bits x gear_ratio counts per joint revolution.
void read_encoders(const TwinModel& model, TwinState& state) {
  const Geometry& g = state.geometry;
  const Effects& fx = model.config().effects;
  for (int i = 0; i < 3; ++i) {
    double angle = state.last.theta_motor[i];
    const double dt = latch_offset_s(fx, i, state.noise.rng);
    if (dt != 0.0) angle -= dt * state.last.motor_velocity[i];
    angle += encoder_angle_error(fx, i, angle - g.dth_(i));
    state.last.readings[i] = encoder_reading(model.config().encoder, state.noise, angle, g.dth_(i), fx.gear_ratio);
  }
}

int optional_id(const mjModel* m, mjtObj type, const std::string& n) { return mj_name2id(m, type, n.c_str()); }


}  // namespace

MjcfOptions mjcf_with_effects(const TwinConfig& c) {
  MjcfOptions o = c.mjcf;
  o.effects = c.effects.mjcf;
  if (c.effects.drive.any()) drive_train_rotors(c.effects, o.effects);
  return o;
}

void check_transmission(const Robot& actual, const TwinConfig& config) {
  if (config.effects.drive.any()) check_drive_train(actual, config, TwinModel::kMaxOmegaDt);
  const MjcfOptions o = mjcf_with_effects(config);
  for (int i = 0; i < 3; ++i) {
    const double c = o.effects.compliance_rad_per_Nm[static_cast<size_t>(i)];
    if (!(c > 0.0)) continue;
    const double la_m = actual.geometry.la_(i) * kMetresPerMm;
    const double omega = transmission_omega(o, i, la_m);
    if (omega * o.timestep_s > TwinModel::kMaxOmegaDt) {
      throw InputError(fmt::format(
          "effects.transmission_compliance_rad_per_Nm: chain {}: {} rad/N m is too stiff for "
          "physics.timestep_s {} (omega dt = {:.3g} > {}); use a compliance of at least {:.3g} rad/N m "
          "or a timestep of at most {:.3g} s",
          i + 1, c, o.timestep_s, omega * o.timestep_s, TwinModel::kMaxOmegaDt,
          c * std::pow(omega * o.timestep_s / TwinModel::kMaxOmegaDt, 2), TwinModel::kMaxOmegaDt / omega));
    }
    // Behind a compliant transmission the velocity loop acts on the rotor
    // alone: the sampled loop w+ = w - (kv T / Ia) w needs kv T / Ia <= 1 to
    // settle without ringing (at 2 it diverges).
    const ServoDrive& d = config.drives[static_cast<size_t>(i)];
    const double period = 1.0 / config.servo_rate_hz;
    const double gain = d.kv * period / o.armature_kg_m2;
    if (d.mode == ServoMode::kPosition && gain > TwinModel::kMaxRotorLoopGain) {
      const double rate = d.kv / (TwinModel::kMaxRotorLoopGain * o.armature_kg_m2);
      throw InputError(fmt::format(
          "effects.transmission_compliance_rad_per_Nm: chain {}: with a compliant transmission the drive's "
          "velocity loop acts on the rotor (armature {} kg m^2) alone and kv T / armature = {:.3g} > {}: "
          "use servo.rate_hz >= {:.0f} (with physics.timestep_s <= {:.3g}) or servo.kv <= {:.3g}",
          i + 1, o.armature_kg_m2, gain, TwinModel::kMaxRotorLoopGain, std::ceil(rate), 1.0 / std::ceil(rate),
          TwinModel::kMaxRotorLoopGain * o.armature_kg_m2 / period));
    }
  }
}

TwinModel::TwinModel(const Robot& actual, const TwinConfig& config)
    : actual_(actual), config_(config), xml_(mjcf_from_robot(actual, mjcf_with_effects(config))) {
  config_.mjcf.effects = config.effects.mjcf;
  check_transmission(actual, config_);
  const double ratio = 1.0 / (config.servo_rate_hz * config.mjcf.timestep_s);
  steps_per_tick_ = static_cast<int>(std::lround(ratio));
  if (!(config.servo_rate_hz > 0.0) || steps_per_tick_ < 1 ||
      std::abs(ratio - steps_per_tick_) > 1e-9 * ratio) {
    throw InputError(fmt::format(
        "servo.rate_hz: {} Hz is not a whole fraction of the physics rate {} Hz (timestep {} s)",
        config.servo_rate_hz, 1.0 / config.mjcf.timestep_s, config.mjcf.timestep_s));
  }
  for (auto& dr : config_.drives) dr.period_s = 1.0 / config.servo_rate_hz;
  model_ = load_model_from_xml(xml_);
  const mjModel* m = model_.get();
  for (int i = 0; i < 3; ++i) {
    const int ja = require_id(m, mjOBJ_JOINT, name("joint_a", i).c_str());
    const int jb = require_id(m, mjOBJ_JOINT, name("joint_b", i).c_str());
    qpos_a[i] = m->jnt_qposadr[ja];
    dof_a[i] = m->jnt_dofadr[ja];
    qpos_b[i] = m->jnt_qposadr[jb];
    const int jm = optional_id(m, mjOBJ_JOINT, name("joint_m", i));
    compliant[i] = jm >= 0;
    qpos_m[i] = compliant[i] ? m->jnt_qposadr[jm] : qpos_a[i];
    dof_m[i] = compliant[i] ? m->jnt_dofadr[jm] : dof_a[i];
    actuator[i] = require_id(m, mjOBJ_ACTUATOR, name("motor_a", i).c_str());
    site_tip[i] = require_id(m, mjOBJ_SITE, name("tip_b", i).c_str());
    site_side[i] = optional_id(m, mjOBJ_SITE, name("side_b", i));
    body_base[i] = require_id(m, mjOBJ_BODY, name("link_a", i).c_str());
    body_rotor[i] = compliant[i] ? require_id(m, mjOBJ_BODY, name("rotor_a", i).c_str()) : -1;
    body_elbow[i] = require_id(m, mjOBJ_BODY, name("link_b", i).c_str());
    // Chains 2 and 3 close by a connect, or with clearance by a limited tendon.
    eq_close[i] = i == 0 ? -1 : optional_id(m, mjOBJ_EQUALITY, name("close_b", i));
    const int loose = i == 0 ? -1 : optional_id(m, mjOBJ_TENDON, name("clear_b", i));
    hub_play_m[i] = loose >= 0 ? m->tendon_range[2 * loose + 1] : 0.0;
    if (i > 0 && eq_close[i] < 0 && loose < 0) throw SimError(fmt::format("MuJoCo model: chain {} is not closed", i + 1));
  }
  // A compliant drive's rotor is a one-dof tree no other constraint row
  // touches: its frictionloss row is solved in closed form by twin_step.
  for (int i = 0; i < 3; ++i)
    if (compliant[i] && model_->dof_frictionloss[dof_m[i]] > 0.0)
      rotor_friction[i] = take_rotor_friction(model_.get(), dof_m[i], actuator[i]);
  if (config.effects.drive.any())
    drive_train = make_drive_train(model_.get(), config.effects, qpos_m, qpos_a, dof_m, dof_a, actuator, rotor_friction);
  site_ee = require_id(m, mjOBJ_SITE, "ee");
  body_ee = require_id(m, mjOBJ_BODY, "ee");
  for (int i = 0; i < 3; ++i) {  // hub pin offsets (models/hub_pins.hpp): chains close at pin_b{i}
    const int pin = optional_id(m, mjOBJ_SITE, name("pin_b", i));
    site_pin[i] = pin >= 0 ? pin : site_ee;
  }
}

void apply_geometry(const TwinModel& model, TwinState& state, const Geometry& g) {
  state.geometry = g;
  mjModel* m = state.thermal_model.get();
  if (!m) return;
  for (int i = 0; i < 3; ++i) {
    const double la_m = g.la_(i) * kMetresPerMm, lb_m = g.lb_(i) * kMetresPerMm;
    for (const int body : {model.body_base[i], model.body_rotor[i]}) {
      if (body < 0) continue;
      m->body_pos[3 * body + 0] = g[xa(i)] * kMetresPerMm;
      m->body_pos[3 * body + 1] = g[ya(i)] * kMetresPerMm;
    }
    m->body_pos[3 * model.body_elbow[i] + 0] = la_m;
    m->site_pos[3 * model.site_tip[i] + 0] = lb_m;
    if (model.site_side[i] >= 0) m->site_pos[3 * model.site_side[i] + 0] = lb_m;
    if (i == 0) m->body_pos[3 * model.body_ee + 0] = lb_m;  // the hub rides on link_b1
    if (model.eq_close[i] >= 0) m->eq_data[model.eq_close[i] * mjNEQDATA + 0] = lb_m;
  }
}

void apply_thermal_growth(const TwinModel& model, TwinState& state, double growth) {
  apply_geometry(model, state, thermal_geometry(model.actual().geometry, growth));
  state.last.growth = growth;
  state.last.growth_base = growth;
}

namespace {

// geometry_at_time with the thermal growth of the links and of the base at t_s already computed.
Geometry geometry_with_growth(const TwinModel& model, double t_s, double growth, double growth_base) {
  const TwinConfig& c = model.config();
  const Geometry g = c.events.empty() ? model.actual().geometry : geometry_at(model.actual().geometry, c.events, t_s);
  return c.effects.thermal.on() ? thermal_geometry(g, growth, growth_base) : g;
}

}  // namespace

Geometry geometry_at_time(const TwinModel& model, double t_s) {
  const ThermalEffect& th = model.config().effects.thermal;
  return geometry_with_growth(model, t_s, th.growth(t_s), th.base_growth(t_s));
}

TwinState::TwinState(const TwinModel& model, unsigned long long seed)
    : data(mj_makeData(model.mj())), noise(seed), geometry(model.actual().geometry) {
  if (!data) throw SimError("MuJoCo: cannot allocate mjData");
  if (model.config().effects.thermal.on() || !model.config().events.empty()) {
    thermal_model.reset(mj_copyModel(nullptr, model.mj()));
    if (!thermal_model) throw SimError("MuJoCo: cannot copy the model for thermal growth or events");
  }
  mj_forward(model.mj(), data.get());
  twin_sense(model, *this);
  command_position = last.readings;
}

double constraint_violation_m(const TwinModel& model, const mjData* d) {
  double worst = 0.0;
  for (int i = 1; i < 3; ++i)
    worst = std::max(worst, (site_pos(d, model.site_tip[i]) - site_pos(d, model.site_pin[i])).norm() - model.hub_play_m[i]);
  return worst;
}

void twin_command(TwinState& state, const Eigen::Vector3d& position, const Eigen::Vector3d& velocity) {
  state.command_position = position;
  state.command_velocity = velocity;
}

void twin_sense(const TwinModel& model, TwinState& state) {
  sense_kinematics(model, state.data.get(), state.last);
  read_encoders(model, state);
  for (int i = 0; i < 3; ++i) state.last.torque[i] = state.servo[i].torque;
}

void twin_step(const TwinModel& model, TwinState& state) {
  const mjModel* m = state_model(model, state);
  mjData* d = state.data.get();
  // Thermal growth follows the (slow, smooth) first-order rise every step and
  // events ramp in (sim/events.hpp): nanometres per step, never a jump.
  if (state.thermal_model) {
    const ThermalEffect& th = model.config().effects.thermal;
    const double growth = th.growth(d->time);  // one exp a step, not two (two with a base law of its own)
    const double growth_base = th.base_own() ? th.base_growth(d->time) : growth;
    apply_geometry(model, state, geometry_with_growth(model, d->time, growth, growth_base));
    state.last.growth = growth;
    state.last.growth_base = growth_base;
  }
  mj_step1(m, d);  // positions, velocities and kinematics at the current time
  sense_kinematics(model, d, state.last);
  if (state.steps % model.steps_per_tick() == 0) {
    read_encoders(model, state);
    const auto& drives = model.config().drives;
    for (int i = 0; i < 3; ++i) {
      const ServoInput in{state.command_position[i], state.command_velocity[i],
                          state.last.readings[i], state.last.motor_velocity[i]};
      d->ctrl[model.actuator[i]] = servo_update(drives[static_cast<size_t>(i)], state.servo[i], in);
      state.last.torque[i] = state.servo[i].torque;
    }
  }
  if (model.drive_train.on) drive_train_step(model.drive_train, m, d, state.servo, state.drive_train);
  for (const RotorFriction& r : model.rotor_friction)
    if (r.dof >= 0) d->qfrc_applied[r.dof] = rotor_friction_torque(m, d, r);
  mj_step2(m, d);
  ++state.steps;
  if (d->warning[mjWARN_BADQACC].number > 0 || !std::isfinite(d->qpos[0])) {
    throw SimError(fmt::format("the simulation diverged at t = {} s (check gains and timestep)",
                               state.last.time_s));
  }
  if (d->warning[mjWARN_CNSTRFULL].number > 0)  // rows dropped: the physics would go on wrong
    throw SimError(fmt::format("MuJoCo: more constraint rows than the model's njmax {} at t = {} s", m->njmax,
                               state.last.time_s));
}

}  // namespace gpm::sim
