#include "calib/global/block_pool.hpp"

namespace gpm::calib::global {

BlockPool::BlockPool(int helpers) {
  for (int i = 0; i < helpers; ++i) threads_.emplace_back([this] { helper_loop(); });
}

BlockPool::~BlockPool() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (auto& t : threads_) t.join();
}

void BlockPool::work(Job& job) {
  for (long b; (b = job.next.fetch_add(1)) < job.blocks;) {
    (*job.fn)(b);
    job.done.fetch_add(1, std::memory_order_release);
  }
}

void BlockPool::helper_loop() {
  long seen = 0;
  for (;;) {
    // Watch for the next job for kSpin, then sleep until woken.
    const auto until = std::chrono::steady_clock::now() + kSpin;
    while (epoch_.load(std::memory_order_acquire) == seen && !stop_.load(std::memory_order_acquire) &&
           std::chrono::steady_clock::now() < until)
      std::this_thread::yield();
    Job* job = nullptr;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return stop_.load() || epoch_.load() != seen; });
      if (stop_) return;
      seen = epoch_.load();
      job = job_;
      if (job) job->active.fetch_add(1);
    }
    if (job) {
      work(*job);
      job->active.fetch_sub(1, std::memory_order_release);
    }
  }
}

void BlockPool::run(long blocks, const std::function<void(long)>& fn) {
  std::lock_guard<std::mutex> serial(run_mutex_);
  Job job;
  job.fn = &fn;
  job.blocks = blocks;
  if (!threads_.empty() && blocks > 1) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      job_ = &job;
      ++epoch_;
    }
    wake_.notify_all();
  }
  work(job);
  // Blocks claimed by helpers may still be running.
  while (job.done.load(std::memory_order_acquire) < blocks) std::this_thread::yield();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    job_ = nullptr;  // no helper joins this job any more
  }
  while (job.active.load(std::memory_order_acquire) > 0) std::this_thread::yield();
}

}  // namespace gpm::calib::global
