// Tests of hw/procedures/cycle_clock.cpp (and hw/clock.cpp's ManualClock):
// simulated time does not wait; paced time waits for each cycle on the
// injected clock and restarts its schedule after an overrun. No wall clock.
#include <gtest/gtest.h>

#include "hw/clock.hpp"
#include "hw/procedures/cycle_clock.hpp"

namespace gpm::hw {
namespace {

TEST(CycleClock, SimulatedTimeAdvancesWithoutWaiting) {
  ManualClock clock;
  CycleClock c(0.01, true, clock);
  for (int k = 0; k < 1000; ++k) c.wait_next();
  EXPECT_NEAR(c.now(), 10.0, 1e-9);
  EXPECT_EQ(clock.waits(), 0);
  EXPECT_EQ(clock.now(), 0.0);
}

TEST(CycleClock, PacedTimeWaitsForEachCycle) {
  ManualClock clock;
  clock.advance(100.0);  // any origin
  CycleClock c(0.01, false, clock);
  for (int k = 0; k < 10; ++k) c.wait_next();
  EXPECT_EQ(clock.waits(), 10);
  EXPECT_NEAR(clock.now(), 100.1, 1e-9);  // each wait ended at its cycle's start
  EXPECT_NEAR(c.now(), 0.1, 1e-9);
  EXPECT_EQ(c.overruns(), 0);
}

TEST(CycleClock, ALateCycleRestartsTheScheduleFromNow) {
  ManualClock clock;
  CycleClock c(0.01, false, clock);
  c.wait_next();              // due 0.01: waits
  clock.advance(0.05);        // the work of this cycle took 5 periods
  c.wait_next();              // due 0.02, now 0.06: late by more than a period
  EXPECT_EQ(c.overruns(), 1);
  EXPECT_NEAR(c.now(), 0.06, 1e-12);
  EXPECT_EQ(clock.waits(), 1);
  c.wait_next();              // due 0.07 from the new schedule
  EXPECT_NEAR(clock.now(), 0.07, 1e-12);
  EXPECT_EQ(clock.waits(), 2);
}

TEST(ManualClock, FollowsTheWallClockWithAnOffsetWhenAsked) {
  ManualClock wall(true);
  const double a = wall.now();
  wall.advance(1000.0);
  EXPECT_GE(wall.now() - a, 1000.0);
  EXPECT_LT(wall.now() - a, 1100.0);
}

}  // namespace
}  // namespace gpm::hw
