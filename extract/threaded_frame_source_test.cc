#include "extract/threaded_frame_source.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>

#include "core/error.h"

namespace hapcine {
namespace {

// Frames 0..count-1 with a small gray image holding the index; throws a
// hapcine::Error instead of frame `fail_at` (if >= 0). Counts the frames it
// produced, so tests can see how far ahead the producer ran.
class CountingSource : public FrameSource {
 public:
  CountingSource(int count, int fail_at = -1, std::chrono::microseconds delay = {})
      : count_(count), fail_at_(fail_at), delay_(delay) {
    info_.path = "counting";
    info_.width = 8;
    info_.height = 4;
    info_.frame_count = count;
  }
  const VideoInfo& info() const override { return info_; }
  bool Next(Frame* frame) override {
    if (delay_.count() > 0) std::this_thread::sleep_for(delay_);
    if (next_ == fail_at_) throw Error(info_.path, "decoder failed at frame " + std::to_string(next_));
    if (next_ >= count_) return false;
    if (frame->gray.empty()) frame->gray.create(4, 8, CV_8UC1);
    frame->gray.setTo(next_ % 256);
    frame->index = next_;
    frame->time_s = next_ / 24.0;
    ++next_;
    produced.store(next_);
    return true;
  }
  std::atomic<int> produced{0};

 private:
  VideoInfo info_;
  int count_, fail_at_;
  std::chrono::microseconds delay_;
  int next_ = 0;
};

TEST(ThreadedFrameSource, DeliversEveryFrameInOrderThenEnds) {
  ThreadedFrameSource source(std::make_unique<CountingSource>(500), 2);
  EXPECT_EQ(source.info().path, "counting");
  EXPECT_EQ(source.info().frame_count, 500);
  Frame f;
  int expected = 0;
  while (source.Next(&f)) {
    ASSERT_EQ(f.index, expected);
    ASSERT_EQ(f.gray.at<uint8_t>(2, 3), expected % 256);  // the pixels belong to that frame
    ++expected;
  }
  EXPECT_EQ(expected, 500);
  EXPECT_FALSE(source.Next(&f));  // the end stays the end
}

TEST(ThreadedFrameSource, EmptySourceEndsAtOnce) {
  ThreadedFrameSource source(std::make_unique<CountingSource>(0));
  Frame f;
  EXPECT_FALSE(source.Next(&f));
}

TEST(ThreadedFrameSource, DecoderErrorArrivesAfterTheFramesBeforeIt) {
  ThreadedFrameSource source(std::make_unique<CountingSource>(100, 7), 3);
  Frame f;
  for (int i = 0; i < 7; ++i) {
    ASSERT_TRUE(source.Next(&f));
    EXPECT_EQ(f.index, i);
  }
  try {
    source.Next(&f);
    FAIL() << "the decoder's error was swallowed";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("decoder failed at frame 7"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(source.Next(&f));  // thrown once, then the end
}

TEST(ThreadedFrameSource, ErrorOnTheFirstFrame) {
  ThreadedFrameSource source(std::make_unique<CountingSource>(10, 0));
  Frame f;
  EXPECT_THROW(source.Next(&f), Error);
}

TEST(ThreadedFrameSource, QueueIsBounded) {
  auto inner = std::make_unique<CountingSource>(1000);
  CountingSource* raw = inner.get();
  ThreadedFrameSource source(std::move(inner), 3);
  Frame f;
  ASSERT_TRUE(source.Next(&f));
  // Give the producer ample time to run ahead; it must stop at the bound:
  // 3 queued + at most 1 being handed over, beyond the one taken.
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_LE(raw->produced.load(), 1 + 3 + 1);
  EXPECT_GE(raw->produced.load(), 1 + 3);
}

TEST(ThreadedFrameSource, ConsumerStoppingEarlyDoesNotDeadlock) {
  // Destroyed while the producer waits for room (fast inner source) ...
  for (int round = 0; round < 20; ++round) {
    ThreadedFrameSource source(std::make_unique<CountingSource>(1000), 1);
    Frame f;
    ASSERT_TRUE(source.Next(&f));
  }
  // ... while it is inside a slow Next() ...
  {
    ThreadedFrameSource source(
        std::make_unique<CountingSource>(1000, -1, std::chrono::microseconds(2000)), 2);
    Frame f;
    ASSERT_TRUE(source.Next(&f));
  }
  // ... and without taking a single frame.
  { ThreadedFrameSource source(std::make_unique<CountingSource>(1000), 2); }
  SUCCEED();
}

TEST(ThreadedFrameSource, RejectsANullSource) {
  EXPECT_THROW(ThreadedFrameSource(nullptr), UsageError);
}

}  // namespace
}  // namespace hapcine
