// A sequence of values built in order, each once, either on a thread of its
// own or on first use (a WebAssembly build has no threads): the decoder's
// octrees, subband by subband, so that a first mesh does not wait for the
// set-up that only finer packets need.
#ifndef MESHWAVE_CORE_DEFERRED_H_
#define MESHWAVE_CORE_DEFERRED_H_

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>
#include <vector>

#include "core/parallel_for.h"  // MW_PARALLEL_SERIAL_ONLY

namespace meshwave {

// Values 0..count-1 built in that order, each once, by one builder (which
// may keep state from one to the next), either on a thread of its own
// started right away or, without one, on the caller's thread as far as a
// Get asks. Get(i) waits only for value i, so the decoder decodes the
// coarse subbands' packets while the finer octrees are still being built.
// If building value k throws, values after k are never built and Get(i)
// rethrows for every i >= k. Safe to call from several threads. The
// destructor stops the builder after the value it is building.
template <class T>
class DeferredSequence {
 public:
  DeferredSequence() = default;
  DeferredSequence(const DeferredSequence&) = delete;
  DeferredSequence& operator=(const DeferredSequence&) = delete;
  ~DeferredSequence() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
  }

  // Sets the builder; starts it now on a thread of its own when
  // `in_background` (and threads exist). At most once per object.
  void Start(bool in_background, size_t count, std::function<T(size_t)> make) {
    make_ = std::move(make);
    values_.resize(count);
#ifdef MW_PARALLEL_SERIAL_ONLY
    in_background = false;
#endif
    if (in_background) {
      thread_ = std::thread([this] {
        while (!stop_ && BuildNext()) {
        }
      });
    }
  }

  size_t size() const { return values_.size(); }

  // Value i (< size()): waits for the builder's thread, or builds the
  // values up to i here if none was started.
  T& Get(size_t i) const {
    std::unique_lock lock(mutex_);
    if (!thread_.joinable()) {
      // No thread: this caller builds the values up to i, one caller at a
      // time (foreground_), the others waiting as they would for a thread.
      while (built_ <= i && !error_) {
        lock.unlock();
        {
          const std::lock_guard build(foreground_);
          BuildNext();  // the next one, whoever built the last
        }
        lock.lock();
      }
    } else {
      ready_.wait(lock, [&] { return built_ > i || error_ != nullptr; });
    }
    if (built_ <= i) std::rethrow_exception(error_);
    return *values_[i];
  }

 private:
  // Builds the next value; false when none is left or building threw.
  bool BuildNext() const {
    size_t i;
    {
      const std::lock_guard lock(mutex_);
      if (built_ == values_.size() || error_) return false;
      i = built_;
    }
    std::unique_ptr<T> value;
    std::exception_ptr error;
    try {
      value = std::make_unique<T>(make_(i));
    } catch (...) {
      error = std::current_exception();
    }
    {
      const std::lock_guard lock(mutex_);
      if (error) {
        error_ = error;
      } else {
        values_[i] = std::move(value);
        built_ = i + 1;
      }
      if (error_ || built_ == values_.size()) make_ = nullptr;  // what it captured
    }
    ready_.notify_all();
    return !error;
  }

  mutable std::function<T(size_t)> make_;
  mutable std::vector<std::unique_ptr<T>> values_;  // [0, built_) ready
  mutable size_t built_ = 0;
  mutable std::exception_ptr error_;
  mutable std::mutex mutex_;
  mutable std::mutex foreground_;  // one caller builds at a time without a thread
  mutable std::condition_variable ready_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace meshwave

#endif  // MESHWAVE_CORE_DEFERRED_H_
