// Tests of render/frame_queue.cpp: every frame reaches the consumer once, in
// order, with its pixels (each a copy: the producer reuses its buffer); the
// queue never holds more than its capacity; a consumer error reaches the
// producer and finish(); destroying an unfinished queue stops its thread.
#include "render/frame_queue.hpp"

#include <atomic>
#include <stdexcept>
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
  // The consumer holds frame 0 until the producer has tried to push more
  // frames than the queue can take; the producer must wait, not drop them.
  std::atomic<int> pushed{0};
  std::atomic<bool> release{false};
  std::atomic<int> consumed{0};
  FrameQueue q(2, [&](const FrameImage&, int) {
    while (!release.load()) std::this_thread::yield();
    consumed.fetch_add(1);
  });
  std::thread producer([&] {
    for (int k = 0; k < 10; ++k) {
      q.push(frame_with(k), k);
      pushed.fetch_add(1);
    }
  });
  // Bounded: at most capacity + 1 (the one being consumed) + 1 (the buffer being filled) get in.
  for (int spin = 0; spin < 20000 && pushed.load() < 4; ++spin) std::this_thread::yield();
  const int before = pushed.load();
  EXPECT_LE(before, 4) << "the queue took more frames than its capacity";
  release = true;
  producer.join();
  q.finish();
  EXPECT_EQ(consumed.load(), 10);
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
