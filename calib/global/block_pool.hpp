// Helper threads that share the blocks of one population evaluation with the
// calling thread. Blocks are claimed from an atomic counter and the caller
// works too, so when the helpers are slow to wake (a busy machine) the caller
// simply does more blocks itself instead of waiting for them. Between jobs a
// helper watches for the next one for a short while (kSpin, yielding the core
// to anyone who wants it) before it sleeps: an optimiser's generations follow
// each other every few tens of microseconds, about the time a sleeping thread
// takes to wake, so a sleeping helper would join each generation late.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace gpm::calib::global {

class BlockPool {
 public:
  // Starts `helpers` threads (0: everything runs on the caller).
  explicit BlockPool(int helpers);
  ~BlockPool();
  BlockPool(const BlockPool&) = delete;
  BlockPool& operator=(const BlockPool&) = delete;

  // Calls fn(b) once for every b in [0, blocks), on the caller and the
  // helpers; returns when all calls have finished. Calls from several
  // threads are serialised.
  void run(long blocks, const std::function<void(long)>& fn);

 private:
  struct Job {
    const std::function<void(long)>* fn;
    long blocks;
    std::atomic<long> next{0};
    std::atomic<long> done{0};
    std::atomic<int> active{0};
  };
  static void work(Job& job);
  void helper_loop();

  // How long a helper watches for the next job before it sleeps.
  static constexpr std::chrono::microseconds kSpin{200};

  std::mutex run_mutex_;  // one run at a time
  std::mutex mutex_;      // guards job_ and the writes of epoch_, stop_
  std::condition_variable wake_;
  Job* job_ = nullptr;
  std::atomic<long> epoch_{0};  // read without the lock while a helper watches
  std::atomic<bool> stop_{false};
  std::vector<std::thread> threads_;
};

}  // namespace gpm::calib::global
