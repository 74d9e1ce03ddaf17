// Independent runs of a study (gpm study effects, gpm study population) on a
// few threads: each run is a task of its own, its result stored by the
// caller; the results are handed over one at a time.
#pragma once

#include <cstddef>
#include <functional>

namespace gpm::scenario {

// Runs run(k) for k = 0 .. n - 1 on at most `threads` threads (the caller's
// among them), then done(k) for each under one lock, in the order they
// finish. The first exception a run throws is rethrown once every thread has
// ended (the other runs go on); done is not called for that run.
void run_in_parallel(std::size_t n, int threads, const std::function<void(std::size_t)>& run,
                     const std::function<void(std::size_t)>& done);

}  // namespace gpm::scenario
