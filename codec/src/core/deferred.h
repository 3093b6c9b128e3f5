// A sequence of values built in order, each once, on first use: the
// decoder's octrees, subband by subband, so that a packet waits only for its
// own subband's and nothing is built that no packet needs.
#ifndef MESHWAVE_CORE_DEFERRED_H_
#define MESHWAVE_CORE_DEFERRED_H_

#include <cstddef>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

namespace meshwave {

// Values 0..count-1 built in that order, each once, by one builder (which
// may keep state from one to the next), on the first Get that needs them:
// Get(i) builds the values up to i on the caller's thread, one caller at a
// time, so several threads (the decoder's and its work-ahead thread,
// core/work_ahead.h) share the building. If building value k throws,
// values after k are never built and Get(i) rethrows for every i >= k.
template <class T>
class DeferredSequence {
 public:
  DeferredSequence() = default;
  DeferredSequence(const DeferredSequence&) = delete;
  DeferredSequence& operator=(const DeferredSequence&) = delete;

  // Sets the builder. At most once per object, before any Get.
  void Start(size_t count, std::function<T(size_t)> make) {
    make_ = std::move(make);
    values_.resize(count);
  }

  size_t size() const { return values_.size(); }

  // Value i (< size()), built here with those before it if need be. A
  // value already built is returned without waiting for one being built.
  T& Get(size_t i) const {
    std::unique_lock lock(mutex_);
    while (built_ <= i && !error_) {
      lock.unlock();
      {
        const std::lock_guard build(building_);
        BuildNext();  // the next one, whoever built the last
      }
      lock.lock();
    }
    if (built_ <= i) std::rethrow_exception(error_);
    return *values_[i];
  }

 private:
  // Builds the next value, if any (building_ held), or records what
  // building it threw.
  void BuildNext() const {
    size_t i;
    {
      const std::lock_guard lock(mutex_);
      if (built_ == values_.size() || error_) return;
      i = built_;
    }
    std::unique_ptr<T> value;
    std::exception_ptr error;
    try {
      value = std::make_unique<T>(make_(i));
    } catch (...) {
      error = std::current_exception();
    }
    const std::lock_guard lock(mutex_);
    if (error) {
      error_ = error;
    } else {
      values_[i] = std::move(value);
      built_ = i + 1;
    }
    if (error_ || built_ == values_.size()) make_ = nullptr;  // what it captured
  }

  mutable std::function<T(size_t)> make_;
  mutable std::vector<std::unique_ptr<T>> values_;  // [0, built_) ready
  mutable size_t built_ = 0;
  mutable std::exception_ptr error_;
  mutable std::mutex mutex_;     // built_, values_, error_
  mutable std::mutex building_;  // one caller builds at a time
};

}  // namespace meshwave

#endif  // MESHWAVE_CORE_DEFERRED_H_
