#pragma once
// A small blocking FIFO between one producer thread and one consumer
// thread, for pipelining stages (tracking beside estimation): bounded, so
// memory stays flat however far the producer could run ahead.
//
//  - Push() blocks while full; returns false once the consumer has called
//    Cancel() (the producer should stop).
//  - Pop() blocks while empty; returns false at the end (after Finish());
//    if the producer finished with an error, Pop() rethrows it once, after
//    the items pushed before it.
//  - Cancel() (consumer leaving early) wakes a blocked producer; nothing
//    deadlocks.

#include <algorithm>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <utility>

namespace hapcine {

template <typename T>
class BoundedQueue {
 public:
  explicit BoundedQueue(size_t capacity) : capacity_(std::max<size_t>(1, capacity)) {}

  bool Push(T item) {
    std::unique_lock<std::mutex> lock(mutex_);
    room_.wait(lock, [&] { return cancelled_ || items_.size() < capacity_; });
    if (cancelled_) return false;
    items_.push_back(std::move(item));
    lock.unlock();
    ready_.notify_one();
    return true;
  }

  // Producer: no more items; `error` (if any) is rethrown by Pop().
  void Finish(std::exception_ptr error = nullptr) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      finished_ = true;
      error_ = error;
    }
    ready_.notify_all();
  }

  bool Pop(T* item) {
    std::unique_lock<std::mutex> lock(mutex_);
    ready_.wait(lock, [&] { return !items_.empty() || finished_; });
    if (items_.empty()) {
      if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
      return false;
    }
    *item = std::move(items_.front());
    items_.pop_front();
    lock.unlock();
    room_.notify_one();
    return true;
  }

  // Consumer: stop the producer (its next or current Push returns false).
  void Cancel() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      cancelled_ = true;
    }
    room_.notify_all();
  }

 private:
  const size_t capacity_;
  std::mutex mutex_;
  std::condition_variable ready_, room_;
  std::deque<T> items_;
  bool finished_ = false, cancelled_ = false;
  std::exception_ptr error_;
};

}  // namespace hapcine
