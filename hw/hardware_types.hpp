// Data exchanged with a robot backend each cycle (mutable data, no model):
// the state read from the drives and the command written to them. Joint
// positions are encoder readings theta_m (rad); theta_a = theta_m + dth.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include <Eigen/Core>

#include "models/parameters.hpp"

namespace gpm::hw {

// What a joint's drive is asked to do.
enum class JointMode : std::uint8_t {
  kTorqueOff,  // drive disabled: no torque, only the encoder is read
  kPosition,   // drive closes its position loop on the command
};

// Text name of a joint mode ("position", "torque_off").
const char* joint_mode_name(JointMode mode);

// One drive's status as it reports it.
struct DriveStatus {
  bool enabled = false;          // power stage on, following commands
  bool fault = false;            // drive reports a fault
  std::uint16_t status_word = 0; // raw status word
  std::uint16_t fault_code = 0;  // drive-specific fault code (0 = none)
};

// State of the three joints at one instant.
struct HardwareState {
  double time_s = 0.0;                                 // backend time of the reading
  // When each joint's reading was taken (s, backend time): time_s for all
  // where the drives copy their positions at one instant (a latch, the twin);
  // each reply's time where they are polled one after another.
  Eigen::Vector3d read_time_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d theta_m = Eigen::Vector3d::Zero();  // encoder readings (rad)
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero(); // rad/s
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();   // N m (0 where the drive does not report it)
  bool torque_reported = false;                        // the drives report their torque (torque is measured)
  std::array<DriveStatus, kNumChains> drive{};
};

// The three readings of st carried to joint 1's read instant by their rates:
// theta_m_i + velocity_i (read_time_s_1 - read_time_s_i) (drives polled one
// after another; readings of one instant are returned as they are).
inline Eigen::Vector3d readings_at_first_read(const HardwareState& st) {
  return st.theta_m + st.velocity.cwiseProduct(Eigen::Vector3d::Constant(st.read_time_s[0]) - st.read_time_s);
}

// Command for the three joints.
struct HardwareCommand {
  Eigen::Vector3d theta_m = Eigen::Vector3d::Zero();  // position targets (rad), encoder space
  std::array<JointMode, kNumChains> mode{JointMode::kTorqueOff, JointMode::kTorqueOff,
                                         JointMode::kTorqueOff};
};

// A command that holds every joint in position mode at theta_m.
HardwareCommand hold_command(const Eigen::Vector3d& theta_m);

}  // namespace gpm::hw
