// Tests of hw/cycle_clock.cpp: simulated time does not sleep; wall time paces.
#include <chrono>

#include <gtest/gtest.h>

#include "hw/cycle_clock.hpp"

namespace gpm::hw {
namespace {

using Clock = std::chrono::steady_clock;

TEST(CycleClock, SimulatedTimeAdvancesWithoutSleeping) {
  CycleClock c(0.01, true);
  const auto t0 = Clock::now();
  for (int k = 0; k < 1000; ++k) c.wait_next();
  EXPECT_NEAR(c.now(), 10.0, 1e-9);
  EXPECT_LT(std::chrono::duration<double>(Clock::now() - t0).count(), 0.5);
}

TEST(CycleClock, WallClockPacesTheCycles) {
  CycleClock c(0.01, false);
  const auto t0 = Clock::now();
  for (int k = 0; k < 10; ++k) c.wait_next();
  EXPECT_GE(std::chrono::duration<double>(Clock::now() - t0).count(), 0.095);
  EXPECT_GE(c.now(), 0.1 - 1e-9);
}

}  // namespace
}  // namespace gpm::hw
