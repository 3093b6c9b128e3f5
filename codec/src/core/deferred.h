// A value built once, either on a thread of its own started right away or,
// where that is not wanted or possible (a WebAssembly build without
// threads), on its first use. Get() is the same either way: it waits for or
// builds the value, rethrows what building it threw, and is safe to call
// from several threads. The decoder uses it to show a first mesh while the
// parts of its set-up that only later packets and finer meshes need are
// still being built.
#ifndef MESHWAVE_CORE_DEFERRED_H_
#define MESHWAVE_CORE_DEFERRED_H_

#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>

#include "core/parallel_for.h"  // MW_PARALLEL_SERIAL_ONLY

namespace meshwave {

template <class T>
class Deferred {
 public:
  Deferred() = default;
  Deferred(const Deferred&) = delete;
  Deferred& operator=(const Deferred&) = delete;
  // Waits for a value still being built: its thread reads what the owner
  // gave it.
  ~Deferred() {
    if (thread_.joinable()) thread_.join();
  }

  // Sets what builds the value; starts it now on a thread of its own when
  // `in_background` (and threads exist). At most once per object.
  void Start(bool in_background, std::function<T()> make) {
    make_ = std::move(make);
#ifdef MW_PARALLEL_SERIAL_ONLY
    in_background = false;
#endif
    if (in_background) thread_ = std::thread([this] { Build(); });
  }

  // The value: waits for its thread, or builds it here if none was started.
  T& Get() const {
    std::call_once(once_, [this] {
      if (thread_.joinable()) {
        thread_.join();
      } else {
        Build();
      }
    });
    if (error_) std::rethrow_exception(error_);
    return *value_;
  }

 private:
  void Build() const {
    try {
      value_.emplace(make_());
    } catch (...) {
      error_ = std::current_exception();
    }
    make_ = nullptr;  // what it captured is not needed any more
  }

  mutable std::function<T()> make_;
  mutable std::optional<T> value_;
  mutable std::exception_ptr error_;
  mutable std::thread thread_;
  mutable std::once_flag once_;
};

}  // namespace meshwave

#endif  // MESHWAVE_CORE_DEFERRED_H_
