#include "sim/oracle_command.hpp"

#include "models/kinematics.hpp"
#include "sim/encoder_error.hpp"
#include "sim/twin.hpp"

namespace gpm::sim {

namespace {

// Fixed-point steps of theta_m = theta_a + TE(theta_m) - TE(home): each
// shrinks the error by |dTE/dtheta_m| (below 1e-2 for the plausible ranges).
constexpr int kMotorSteps = 4;

// The motor angle (rad) that puts link k at theta_a through its mesh's transmission error.
double motor_angle(const DriveTrainModel& dm, std::size_t k, double theta_a) {
  if (!dm.on || !dm.mesh[k]) return theta_a;
  double theta_m = theta_a;
  for (int s = 0; s < kMotorSteps; ++s)
    theta_m = theta_a + transmission_error(dm.chain[k], theta_m, dm.gear_ratio, dm.te_motor_order) - dm.te_home[k];
  return theta_m;
}

}  // namespace

Eigen::Vector3d oracle_readings(const TwinModel& model, const Eigen::Vector3d& theta_a, const Eigen::Vector3d& dth) {
  const Effects& fx = model.config().effects;
  Eigen::Vector3d out;
  for (int i = 0; i < 3; ++i) {
    const double r = motor_angle(model.drive_train, static_cast<std::size_t>(i), theta_a[i]) - dth[i];
    out[i] = wrap_2pi(r + encoder_angle_error(fx, i, r));
  }
  return out;
}

}  // namespace gpm::sim
