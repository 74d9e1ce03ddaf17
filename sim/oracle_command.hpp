// The floor's controller (run/compensation.hpp): commands that know the
// twin's own reading effects as well as its actual geometry. Link i stands
// at theta_a when its motor stands at theta_m with
//   theta_m = theta_a + TE(theta_m) - TE(theta_m0)
// (the reducer's transmission error where the chain has a mesh,
// sim/drive_train.hpp, zero at the motor's home theta_m0), and its encoder
// then reads r + e(r), r = theta_m - dth (sim/encoder_error.hpp). What the
// twin does not fix by the pose (backlash flank, twist under load,
// quantisation, thermal growth since the start) stays the floor's error.
#pragma once

#include <Eigen/Core>

namespace gpm::sim {

class TwinModel;

// The readings (rad, each in [0, 2 pi)) the drives must hold for the links to
// stand at theta_a (rad) on model's twin, dth the encoder offsets of its
// actual geometry; the motor angle solved by fixed-point steps (TE changes
// by far less than 1 rad per rad).
Eigen::Vector3d oracle_readings(const TwinModel& model, const Eigen::Vector3d& theta_a, const Eigen::Vector3d& dth);

}  // namespace gpm::sim
