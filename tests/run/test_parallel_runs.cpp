// Tests of run/parallel_runs.cpp: every run once, each finished run handed
// over once, a run's exception rethrown after the others ran, and more
// threads than runs.
#include "run/parallel_runs.hpp"

#include <atomic>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

namespace gpm::scenario {
namespace {

TEST(ParallelRuns, EveryRunOnceAndEachHandedOverOnce) {
  for (int threads : {1, 2, 5}) {
    std::vector<std::atomic<int>> ran(7);
    std::vector<int> handed(7, 0);
    run_in_parallel(7, threads, [&](std::size_t k) { ++ran[k]; }, [&](std::size_t k) { ++handed[k]; });
    for (std::size_t k = 0; k < 7; ++k) {
      EXPECT_EQ(ran[k].load(), 1) << k;
      EXPECT_EQ(handed[k], 1) << k;
    }
  }
}

TEST(ParallelRuns, AFailedRunIsRethrownAfterTheOthers) {
  std::vector<int> handed(5, 0);
  EXPECT_THROW(run_in_parallel(
                   5, 2,
                   [](std::size_t k) {
                     if (k == 2) throw std::runtime_error("run 2");
                   },
                   [&](std::size_t k) { ++handed[k]; }),
               std::runtime_error);
  EXPECT_EQ(handed, (std::vector<int>{1, 1, 0, 1, 1}));
}

}  // namespace
}  // namespace gpm::scenario
