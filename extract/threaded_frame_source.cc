#include "extract/threaded_frame_source.h"

#include <algorithm>
#include <utility>

#include "core/error.h"

namespace hapcine {

ThreadedFrameSource::ThreadedFrameSource(std::unique_ptr<FrameSource> inner, int capacity)
    : inner_(std::move(inner)), capacity_(static_cast<size_t>(std::max(1, capacity))) {
  if (!inner_) throw UsageError("ThreadedFrameSource needs a frame source");
  info_ = inner_->info();
  producer_ = std::thread([this] { Produce(); });
}

ThreadedFrameSource::~ThreadedFrameSource() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    consumer_gone_ = true;
  }
  room_cv_.notify_all();
  producer_.join();
}

void ThreadedFrameSource::Produce() {
  try {
    for (;;) {
      Frame frame;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        room_cv_.wait(lock, [&] { return consumer_gone_ || ready_.size() < capacity_; });
        if (consumer_gone_) break;
        if (!spare_.empty()) {  // its buffers are reused when nobody else holds them
          frame = std::move(spare_.back());
          spare_.pop_back();
        }
      }
      // Decoding happens outside the lock: the consumer keeps taking frames.
      if (!inner_->Next(&frame)) break;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        ready_.push_back(std::move(frame));
      }
      ready_cv_.notify_one();
    }
  } catch (...) {
    std::lock_guard<std::mutex> lock(mutex_);
    error_ = std::current_exception();
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    producer_done_ = true;
  }
  ready_cv_.notify_all();
}

bool ThreadedFrameSource::Next(Frame* frame) {
  std::unique_lock<std::mutex> lock(mutex_);
  ready_cv_.wait(lock, [&] { return !ready_.empty() || producer_done_; });
  if (ready_.empty()) {
    if (error_) {
      std::exception_ptr e = std::exchange(error_, nullptr);  // thrown once
      std::rethrow_exception(e);
    }
    return false;
  }
  Frame previous = std::move(*frame);
  *frame = std::move(ready_.front());
  ready_.pop_front();
  if (spare_.size() < 2) spare_.push_back(std::move(previous));
  lock.unlock();
  room_cv_.notify_one();
  return true;
}

std::vector<double> ThreadedFrameSource::SkippedAtEnd() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return producer_done_ ? inner_->SkippedAtEnd() : std::vector<double>{};
}

std::vector<std::string> ThreadedFrameSource::Warnings() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return producer_done_ ? inner_->Warnings() : std::vector<std::string>{};
}

}  // namespace hapcine
