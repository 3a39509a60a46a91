#include "extract/bounded_queue.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>

namespace hapcine {
namespace {

TEST(BoundedQueue, OrderAcrossThreadsThenTheEnd) {
  BoundedQueue<int> q(4);
  std::thread producer([&] {
    for (int i = 0; i < 1000; ++i) ASSERT_TRUE(q.Push(i));
    q.Finish();
  });
  int v = -1, expected = 0;
  while (q.Pop(&v)) ASSERT_EQ(v, expected++);
  producer.join();
  EXPECT_EQ(expected, 1000);
  EXPECT_FALSE(q.Pop(&v));
}

TEST(BoundedQueue, ErrorAfterTheItemsBeforeIt) {
  BoundedQueue<int> q(8);
  q.Push(1);
  q.Push(2);
  q.Finish(std::make_exception_ptr(std::runtime_error("tracker failed")));
  int v = 0;
  ASSERT_TRUE(q.Pop(&v));
  EXPECT_EQ(v, 1);
  ASSERT_TRUE(q.Pop(&v));
  EXPECT_EQ(v, 2);
  EXPECT_THROW(q.Pop(&v), std::runtime_error);
  EXPECT_FALSE(q.Pop(&v));  // thrown once
}

TEST(BoundedQueue, FullQueueBlocksUntilCancelled) {
  BoundedQueue<int> q(2);
  std::atomic<int> pushed{0};
  bool last_push = true;
  std::thread producer([&] {
    for (int i = 0; i < 10; ++i) {
      last_push = q.Push(i);
      if (!last_push) return;
      ++pushed;
    }
  });
  // Wait for the two pushes that fit (however slowly a loaded machine runs
  // the producer), then give the third one time to get through if it could.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (pushed.load() < 2 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  EXPECT_EQ(pushed.load(), 2);  // bounded: the third Push waits
  q.Cancel();                   // the consumer leaves: no deadlock
  producer.join();
  EXPECT_FALSE(last_push);
  EXPECT_EQ(pushed.load(), 2);
}

TEST(BoundedQueue, ZeroCapacityMeansOne) {
  BoundedQueue<int> q(0);
  EXPECT_TRUE(q.Push(5));
  int v = 0;
  ASSERT_TRUE(q.Pop(&v));
  EXPECT_EQ(v, 5);
}

}  // namespace
}  // namespace hapcine
