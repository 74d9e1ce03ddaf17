// Tests of hw/robot_hardware.cpp: the lifecycle refuses misuse and a backend
// failure enters the error state.
#include <gtest/gtest.h>

#include "hw/hw_errors.hpp"
#include "hw_test_util.hpp"

namespace gpm::hw {
namespace {

const Eigen::Vector3d kHome(1.1111317324, 3.1106801435, 4.8248530725);

TEST(RobotHardware, WriteBeforeActivateIsRefused) {
  test::RecordingBackend hw(kHome);
  EXPECT_THROW(hw.write(hold_command(kHome), 0.0), LifecycleError);
  hw.configure();
  EXPECT_THROW(hw.write(hold_command(kHome), 0.0), LifecycleError);
  EXPECT_EQ(hw.state(), LifecycleState::kInactive);
}

TEST(RobotHardware, ActivateTwiceIsRefused) {
  test::RecordingBackend hw(kHome);
  EXPECT_THROW(hw.activate(), LifecycleError);  // not configured
  hw.configure();
  hw.activate();
  EXPECT_THROW(hw.activate(), LifecycleError);
  EXPECT_THROW(hw.configure(), LifecycleError);
  EXPECT_EQ(hw.state(), LifecycleState::kActive);
}

TEST(RobotHardware, ReadBeforeConfigureIsRefused) {
  test::RecordingBackend hw(kHome);
  EXPECT_THROW(hw.read(0.0), LifecycleError);
}

TEST(RobotHardware, FullCycle) {
  test::RecordingBackend hw(kHome);
  std::vector<HardwareCommand> rec;
  hw.record = &rec;
  hw.configure();
  hw.activate();
  hw.write(hold_command(kHome), 0.0);
  EXPECT_EQ(hw.read(0.004).drive[0].enabled, true);
  hw.deactivate();
  EXPECT_EQ(hw.state(), LifecycleState::kInactive);
  EXPECT_FALSE(hw.read(0.008).drive[0].enabled);
  hw.shutdown();
  EXPECT_EQ(hw.state(), LifecycleState::kFinalized);
  EXPECT_THROW(hw.read(0.0), LifecycleError);
  EXPECT_EQ(rec.size(), 1u);
}

TEST(RobotHardware, BackendFailureEntersErrorWithDrivesDisabled) {
  test::RecordingBackend hw(kHome);
  hw.configure();
  hw.activate();
  hw.fail_reads = true;
  EXPECT_THROW(hw.read(0.0), HardwareError);
  EXPECT_EQ(hw.state(), LifecycleState::kError);
  EXPECT_NE(hw.error_message().find("read failed"), std::string::npos);
  EXPECT_THROW(hw.write(hold_command(kHome), 0.0), LifecycleError);
  EXPECT_THROW(hw.activate(), LifecycleError);
  hw.fail_reads = false;
  hw.reset();
  EXPECT_EQ(hw.state(), LifecycleState::kUnconfigured);
  hw.configure();
  EXPECT_FALSE(hw.read(0.0).drive[1].enabled);
}

TEST(RobotHardware, EmergencyStopFromAnyState) {
  test::RecordingBackend hw(kHome);
  hw.configure();
  hw.activate();
  hw.emergency_stop("button");
  EXPECT_EQ(hw.state(), LifecycleState::kError);
  EXPECT_EQ(hw.error_message(), "emergency stop: button");
  EXPECT_THROW(hw.write(hold_command(kHome), 0.0), LifecycleError);
}

}  // namespace
}  // namespace gpm::hw
