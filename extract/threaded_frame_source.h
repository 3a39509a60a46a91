#pragma once
// Decoding in its own thread: a FrameSource that runs another one's Next()
// on a producer thread and hands the frames over through a small bounded
// queue, so decoding + scaling overlap tracking and estimation on the
// caller's thread.
//
//  - Order: frames come out exactly in the inner source's order.
//  - Memory: at most `capacity` decoded frames wait in the queue (plus the
//    one being decoded and the caller's), whatever the video's length;
//    consumed frames' buffers go back to the producer for reuse.
//  - Errors: an exception thrown by the inner Next() is rethrown by Next()
//    on the caller's thread, after the frames decoded before it.
//  - Early stop: destroying the source while the producer waits for room
//    (or decodes) stops and joins it; nothing deadlocks.

#include <condition_variable>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "extract/frame_source.h"

namespace hapcine {

class ThreadedFrameSource : public FrameSource {
 public:
  // capacity >= 1: decoded frames allowed to wait for the consumer.
  ThreadedFrameSource(std::unique_ptr<FrameSource> inner, int capacity = 3);
  ~ThreadedFrameSource() override;
  ThreadedFrameSource(const ThreadedFrameSource&) = delete;
  ThreadedFrameSource& operator=(const ThreadedFrameSource&) = delete;

  // The inner source's info, read once before the producer starts (the
  // inner source is not touched from this thread afterwards).
  const VideoInfo& info() const override { return info_; }
  bool Next(Frame* frame) override;
  // The inner source's, once Next() returned false (the producer is done).
  std::vector<double> SkippedAtEnd() const override;
  std::vector<std::string> Warnings() const override;

 private:
  void Produce();

  std::unique_ptr<FrameSource> inner_;
  VideoInfo info_;
  const size_t capacity_;
  mutable std::mutex mutex_;
  std::condition_variable ready_cv_;  // a frame was queued, or the producer ended
  std::condition_variable room_cv_;   // a frame was taken, or the consumer left
  std::deque<Frame> ready_;           // decoded, waiting for the consumer
  std::vector<Frame> spare_;          // consumed frames whose buffers can be reused
  bool producer_done_ = false;
  bool consumer_gone_ = false;
  std::exception_ptr error_;
  std::thread producer_;
};

}  // namespace hapcine
