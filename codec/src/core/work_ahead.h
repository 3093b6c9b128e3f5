// Steps 0..n-1 run in order on a thread of their own, each one something
// the owner's callers would otherwise do on first use (build a level's
// tables, say), so that they usually find it done. Stopping early loses
// nothing but that head start, so the destructor stops after the step under
// way instead of running the rest: a decoder that drew a coarse mesh and is
// destroyed does not wait for the finest level's tables it never needed.
//
// The steps must be safe to run while callers do the same work on first
// use (each value built once, whoever comes first). A step that throws ends
// the run: the callers meet the error again on their own use. A WebAssembly
// build without threads runs nothing ahead.
#ifndef MESHWAVE_CORE_WORK_AHEAD_H_
#define MESHWAVE_CORE_WORK_AHEAD_H_

#include <atomic>
#include <cstddef>
#include <functional>
#include <utility>

#include "core/parallel_for.h"  // MW_PARALLEL_SERIAL_ONLY

#ifndef MW_PARALLEL_SERIAL_ONLY
#include <thread>
#endif

namespace meshwave {

class WorkAhead {
 public:
  WorkAhead() = default;
  WorkAhead(const WorkAhead&) = delete;
  WorkAhead& operator=(const WorkAhead&) = delete;
  ~WorkAhead() { Stop(); }

  // Starts running step(0) .. step(count - 1) on a new thread. At most once.
  void Start(size_t count, std::function<void(size_t)> step) {
#ifndef MW_PARALLEL_SERIAL_ONLY
    step_ = std::move(step);
    thread_ = std::thread([this, count] {
      try {
        for (size_t i = 0; i < count && !stop_.load(std::memory_order_relaxed); ++i) step_(i);
      } catch (...) {  // the caller that needs the value meets the error
      }
    });
#else
    (void)count;
    (void)step;
#endif
  }

  // Whether Stop was asked: a long step may give up between its parts.
  bool stopping() const { return stop_.load(std::memory_order_relaxed); }

  // No step starts after this returns; the one under way has finished.
  void Stop() {
    stop_ = true;
#ifndef MW_PARALLEL_SERIAL_ONLY
    if (thread_.joinable()) thread_.join();
#endif
  }

 private:
  std::atomic<bool> stop_{false};
  std::function<void(size_t)> step_;
#ifndef MW_PARALLEL_SERIAL_ONLY
  std::thread thread_;
#endif
};

}  // namespace meshwave

#endif  // MESHWAVE_CORE_WORK_AHEAD_H_
