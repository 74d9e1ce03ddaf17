// Rendering and encoding overlapped: the thread that renders (it owns the
// OpenGL context) hands copies of its frames to one consumer thread (the
// encoder and PNG writer) through a bounded queue of reusable buffers, so
// that frame k+1 renders while frame k encodes. The consumer sees every frame
// once, in order, so its output is the same as in a sequential loop.
//
// Use:
//   FrameQueue q(3, [&](const FrameImage& f, int k) { encoder.add_frame(f); });
//   for (...) q.push(renderer.render(t), k);   // blocks while 3 frames wait
//   q.finish();                                // drains; rethrows a consumer error
#pragma once

#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "render/frame_image.hpp"

namespace gpm::render {

class FrameQueue {
 public:
  using Consumer = std::function<void(const FrameImage& frame, int index)>;

  // Starts the consumer thread; at most `capacity` (>= 1) frames wait.
  FrameQueue(int capacity, Consumer consume);
  // Stops the consumer (frames still waiting are dropped) and joins it.
  ~FrameQueue();
  FrameQueue(const FrameQueue&) = delete;
  FrameQueue& operator=(const FrameQueue&) = delete;

  // Copies frame into a free buffer and queues it as frame `index`; blocks
  // while the queue is full. Rethrows the consumer's exception if it failed.
  void push(const FrameImage& frame, int index);

  // Waits until every queued frame is consumed and stops the thread;
  // rethrows the consumer's exception if it failed.
  void finish();

 private:
  void run();
  void rethrow_locked();

  Consumer consume_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<FrameImage> buffers_;
  std::deque<std::pair<int, int>> queued_;  // (buffer, frame index), oldest first
  std::vector<int> free_;                   // buffers not in use
  bool closing_ = false, stopping_ = false;
  std::exception_ptr error_;
  std::thread thread_;
};

}  // namespace gpm::render
