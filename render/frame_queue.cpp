#include "render/frame_queue.hpp"

#include <algorithm>

namespace gpm::render {

FrameQueue::FrameQueue(int capacity, Consumer consume) : consume_(std::move(consume)) {
  // capacity waiting frames plus the one being consumed.
  const int n = std::max(1, capacity) + 1;
  buffers_.resize(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) free_.push_back(i);
  thread_ = std::thread([this] { run(); });
}

FrameQueue::~FrameQueue() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void FrameQueue::rethrow_locked() {
  if (error_) std::rethrow_exception(error_);
}

void FrameQueue::push(const FrameImage& frame, int index) {
  int b = -1;
  {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [this] { return !free_.empty() || error_; });
    rethrow_locked();
    b = free_.back();
    free_.pop_back();
  }
  // The copy is made outside the lock: the consumer owns no free buffer.
  FrameImage& dst = buffers_[static_cast<size_t>(b)];
  dst.width = frame.width;
  dst.height = frame.height;
  dst.rgb.assign(frame.rgb.begin(), frame.rgb.end());
  {
    std::lock_guard<std::mutex> lock(mutex_);
    queued_.emplace_back(b, index);
  }
  changed_.notify_all();
}

void FrameQueue::finish() {
  {
    std::unique_lock<std::mutex> lock(mutex_);
    closing_ = true;
    changed_.notify_all();
    changed_.wait(lock, [this] { return queued_.empty() || error_; });
  }
  changed_.notify_all();
  if (thread_.joinable()) thread_.join();
  std::lock_guard<std::mutex> lock(mutex_);
  rethrow_locked();
}

void FrameQueue::run() {
  for (;;) {
    std::pair<int, int> item;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      changed_.wait(lock, [this] { return stopping_ || !queued_.empty() || closing_; });
      if (stopping_ || queued_.empty()) return;  // stopped, or closing with nothing left
      item = queued_.front();
    }
    try {
      consume_(buffers_[static_cast<size_t>(item.first)], item.second);
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex_);
      error_ = std::current_exception();
      queued_.clear();
      changed_.notify_all();
      return;
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      queued_.pop_front();
      free_.push_back(item.first);
    }
    changed_.notify_all();
  }
}

}  // namespace gpm::render
