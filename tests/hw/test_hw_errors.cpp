// Tests of hw/hw_errors.hpp and models/errors.hpp: one hierarchy under
// gpm::Error, so a caller that handles HardwareError also stops on a refused
// command, and one catch of gpm::Error sees every error the toolkit raises.
#include <type_traits>

#include <gtest/gtest.h>

#include "hw/hw_errors.hpp"
#include "models/errors.hpp"

namespace gpm::hw {
namespace {

TEST(HwErrors, EveryErrorIsAGpmError) {
  EXPECT_TRUE((std::is_base_of_v<Error, InputError>));
  EXPECT_TRUE((std::is_base_of_v<Error, HardwareError>));
  EXPECT_TRUE((std::is_base_of_v<Error, LifecycleError>));
  EXPECT_FALSE((std::is_base_of_v<HardwareError, InputError>));
}

TEST(HwErrors, RefusedCommandsAndInterruptionsAreHardwareErrors) {
  EXPECT_TRUE((std::is_base_of_v<HardwareError, SafetyError>));
  EXPECT_TRUE((std::is_base_of_v<HardwareError, CommandRejected>));
  EXPECT_TRUE((std::is_base_of_v<HardwareError, Interrupted>));
  try {
    throw CommandRejected("safety: command refused: joint 1 beyond joint_max");
  } catch (const HardwareError& e) {
    EXPECT_STREQ(e.what(), "safety: command refused: joint 1 beyond joint_max");
    return;
  }
  ADD_FAILURE() << "CommandRejected was not caught as a HardwareError";
}

}  // namespace
}  // namespace gpm::hw
