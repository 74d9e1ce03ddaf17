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
    s.theta_a[i] = d->qpos[model.qpos_a[i]];
    s.theta_b[i] = s.theta_a[i] + d->qpos[model.qpos_b[i]];
    s.velocity[i] = d->qvel[model.dof_a[i]];
  }
  const Eigen::Vector3d ee = site_pos(d, model.site_ee);
  s.ee_mm = Eigen::Vector2d(ee.x(), ee.y()) / kMetresPerMm;
  s.violation_m = constraint_violation_m(model, d);
}

void read_encoders(const TwinModel& model, TwinState& state) {
  const Geometry& g = model.actual().geometry;
  for (int i = 0; i < 3; ++i) {
    state.last.readings[i] =
        encoder_reading(model.config().encoder, state.noise, state.last.theta_a[i], g.dth_(i));
  }
}

}  // namespace

TwinModel::TwinModel(const Robot& actual, const TwinConfig& config)
    : actual_(actual), config_(config), xml_(mjcf_from_robot(actual, config.mjcf)) {
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
    actuator[i] = require_id(m, mjOBJ_ACTUATOR, name("motor_a", i).c_str());
    site_tip[i] = require_id(m, mjOBJ_SITE, name("tip_b", i).c_str());
  }
  site_ee = require_id(m, mjOBJ_SITE, "ee");
}

TwinState::TwinState(const TwinModel& model, unsigned long long seed)
    : data(mj_makeData(model.mj())), noise(seed) {
  if (!data) throw SimError("MuJoCo: cannot allocate mjData");
  mj_forward(model.mj(), data.get());
  twin_sense(model, *this);
  command_position = last.readings;
}

double constraint_violation_m(const TwinModel& model, const mjData* d) {
  const Eigen::Vector3d ee = site_pos(d, model.site_ee);
  double worst = 0.0;
  for (int i = 1; i < 3; ++i) worst = std::max(worst, (site_pos(d, model.site_tip[i]) - ee).norm());
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
  const mjModel* m = model.mj();
  mjData* d = state.data.get();
  mj_step1(m, d);  // positions, velocities and kinematics at the current time
  sense_kinematics(model, d, state.last);
  if (state.steps % model.steps_per_tick() == 0) {
    read_encoders(model, state);
    const auto& drives = model.config().drives;
    for (int i = 0; i < 3; ++i) {
      const ServoInput in{state.command_position[i], state.command_velocity[i],
                          state.last.readings[i], state.last.velocity[i]};
      d->ctrl[model.actuator[i]] = servo_update(drives[static_cast<size_t>(i)], state.servo[i], in);
      state.last.torque[i] = state.servo[i].torque;
    }
  }
  mj_step2(m, d);
  ++state.steps;
  if (d->warning[mjWARN_BADQACC].number > 0 || !std::isfinite(d->qpos[0])) {
    throw SimError(fmt::format("the simulation diverged at t = {} s (check gains and timestep)",
                               state.last.time_s));
  }
}

}  // namespace gpm::sim
