#include "run/parallel_runs.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace gpm::scenario {

void run_in_parallel(std::size_t n, int threads, const std::function<void(std::size_t)>& run,
                     const std::function<void(std::size_t)>& done) {
  std::atomic<std::size_t> next{0};
  std::mutex mutex;
  std::exception_ptr bug;
  auto worker = [&] {
    for (std::size_t k = next++; k < n; k = next++) {
      try {
        run(k);
      } catch (...) {
        const std::lock_guard lock(mutex);
        if (!bug) bug = std::current_exception();
        continue;
      }
      const std::lock_guard lock(mutex);
      done(k);
    }
  };
  const int count = std::clamp(threads, 1, static_cast<int>(std::max<std::size_t>(n, 1)));
  std::vector<std::thread> pool;
  for (int t = 1; t < count; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  if (bug) std::rethrow_exception(bug);
}

}  // namespace gpm::scenario
