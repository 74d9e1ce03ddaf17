// Tests of calib/global/block_pool.cpp: every block runs exactly once per run
// with 0, 1 and 3 helpers over many back-to-back runs (helpers watching for
// the next job) and the pool is destroyed while they watch; a helper joins a
// run whose caller is busy; runs from several threads are serialised.
#include "calib/global/block_pool.hpp"

#include <atomic>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace gpm::calib::global {
namespace {

// Runs `blocks` blocks and checks that each was called exactly once.
void expect_each_block_once(BlockPool& pool, long blocks) {
  std::vector<std::atomic<int>> calls(static_cast<size_t>(blocks));
  pool.run(blocks, [&](long b) { calls[static_cast<size_t>(b)].fetch_add(1); });
  for (long b = 0; b < blocks; ++b) ASSERT_EQ(calls[static_cast<size_t>(b)].load(), 1) << "block " << b;
}

TEST(BlockPool, EveryBlockOnceInBackToBackRuns) {
  for (int helpers : {0, 1, 3}) {
    BlockPool pool(helpers);
    for (int run = 0; run < 2000; ++run) expect_each_block_once(pool, 1 + run % 23);
    expect_each_block_once(pool, 0);
  }
}

TEST(BlockPool, HelpersWorkWhenTheCallerIsBusy) {
  // The caller's block does not return until a helper has run another block:
  // only a helper that joined the job can release it.
  BlockPool pool(1);
  for (int run = 0; run < 50; ++run) {
    std::atomic<bool> helper_ran{false};
    const std::thread::id caller = std::this_thread::get_id();
    pool.run(2, [&](long) {
      if (std::this_thread::get_id() != caller) {
        helper_ran = true;
        return;
      }
      while (!helper_ran.load()) std::this_thread::yield();
    });
    EXPECT_TRUE(helper_ran.load());
  }
}

TEST(BlockPool, RunsFromSeveralThreadsAreSerialised) {
  // While a block of one caller's run is in flight, no block of another
  // caller's run may start.
  BlockPool pool(1);
  std::atomic<int> owner{-1}, in_flight{0}, violations{0};
  std::atomic<long> total{0};
  std::vector<std::thread> callers;
  for (int t = 0; t < 3; ++t) {
    callers.emplace_back([&, t] {
      for (int run = 0; run < 300; ++run) {
        pool.run(7, [&](long) {
          int expected = -1;
          if (!owner.compare_exchange_strong(expected, t) && expected != t) violations.fetch_add(1);
          in_flight.fetch_add(1);
          total.fetch_add(1);
          if (in_flight.fetch_sub(1) == 1) {
            int mine = t;
            owner.compare_exchange_strong(mine, -1);
          }
        });
      }
    });
  }
  for (auto& c : callers) c.join();
  EXPECT_EQ(total.load(), 3L * 300 * 7);
  EXPECT_EQ(violations.load(), 0);
}

}  // namespace
}  // namespace gpm::calib::global
