// Tests of render/frame_queue.cpp: every frame reaches the consumer once, in
// order, with its pixels (each a copy: the producer reuses its buffer); the
// queue never holds more than its capacity; a consumer error reaches the
// producer and finish(); destroying an unfinished queue stops its thread.
#include "render/frame_queue.hpp"

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace gpm::render {
namespace {

FrameImage frame_with(int value) {
  FrameImage f;
  f.width = 4;
  f.height = 2;
  f.rgb.assign(24, static_cast<std::uint8_t>(value));
  return f;
}

TEST(FrameQueue, EveryFrameOnceInOrderWithItsPixels) {
  std::vector<int> seen_index, seen_value;
  FrameQueue q(2, [&](const FrameImage& f, int k) {
    seen_index.push_back(k);
    seen_value.push_back(f.rgb.at(23));
  });
  FrameImage reused;  // the producer's single buffer, overwritten every frame
  for (int k = 0; k < 200; ++k) {
    reused = frame_with(k % 251);
    q.push(reused, k + 10);
  }
  q.finish();
  ASSERT_EQ(seen_index.size(), 200u);
  for (int k = 0; k < 200; ++k) {
    EXPECT_EQ(seen_index[static_cast<size_t>(k)], k + 10);
    EXPECT_EQ(seen_value[static_cast<size_t>(k)], k % 251);
  }
}

TEST(FrameQueue, ProducerWaitsWhenTheQueueIsFull) {
  // The consumer holds frame 0 until the frames that fit without it are in
  // (it and the queue's 2), waiting on a condition, not on the wall clock;
  // then no more than capacity + 1 (the one being consumed) + 1 (the buffer
  // being filled) may have got in: the producer waits, it does not drop.
  std::mutex m;
  std::condition_variable changed;
  int pushed = 0, consumed = 0, most_in_while_held = -1;
  FrameQueue q(2, [&](const FrameImage&, int k) {
    std::unique_lock lock(m);
    if (k == 0) {
      changed.wait(lock, [&] { return pushed >= 3; });
      most_in_while_held = pushed;
    }
    ++consumed;
  });
  std::thread producer([&] {
    for (int k = 0; k < 10; ++k) {
      q.push(frame_with(k), k);
      std::lock_guard lock(m);
      ++pushed;
      changed.notify_all();
    }
  });
  producer.join();
  q.finish();
  EXPECT_GE(most_in_while_held, 3);
  EXPECT_LE(most_in_while_held, 4) << "the queue took more frames than its capacity";
  EXPECT_EQ(consumed, 10);
}

TEST(FrameQueue, ConsumerErrorReachesTheProducer) {
  FrameQueue q(1, [](const FrameImage&, int k) {
    if (k == 3) throw std::runtime_error("disk full");
  });
  bool thrown = false;
  try {
    for (int k = 0; k < 100; ++k) q.push(frame_with(k), k);
    q.finish();
  } catch (const std::runtime_error& e) {
    thrown = true;
    EXPECT_STREQ(e.what(), "disk full");
  }
  EXPECT_TRUE(thrown);
}

TEST(FrameQueue, DestroyedUnfinishedStopsItsThread) {
  std::atomic<int> consumed{0};
  {
    FrameQueue q(4, [&](const FrameImage&, int) { consumed.fetch_add(1); });
    q.push(frame_with(1), 0);
  }  // no finish(): joins without hanging
  EXPECT_LE(consumed.load(), 1);
}

}  // namespace
}  // namespace gpm::render
