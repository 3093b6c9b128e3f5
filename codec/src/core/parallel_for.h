// The one home for running work on several threads: loops split into
// contiguous chunks (ParallelFor), a list of tasks taken in order by a few
// workers (ParallelTasks) and a handful of different jobs side by side
// (ParallelInvoke). Threads are started per call and joined before it
// returns (a start costs about 50 µs, so callers keep small loops serial).
//
// Determinism is the caller's part: bodies write only what their own
// indices own, and reductions are made per chunk or per task and combined
// in index order afterwards, so results do not depend on the thread count.
//
// Exceptions: the one a serial run would throw first is rethrown on the
// calling thread, once all threads have joined (others are dropped): every
// chunk runs to its end or its exception and the lowest chunk's wins; tasks
// numbered below one that threw still run, those above it not yet started
// are skipped, and the lowest-numbered exception wins.
//
// A WebAssembly build without threads (emscripten without pthreads) runs
// everything on the calling thread, one after the other; so does any call
// with threads <= 1.
#ifndef MESHWAVE_CORE_PARALLEL_FOR_H_
#define MESHWAVE_CORE_PARALLEL_FOR_H_

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <functional>
#include <utility>
#include <vector>

#if defined(__EMSCRIPTEN__) && !defined(__EMSCRIPTEN_PTHREADS__)
#define MW_PARALLEL_SERIAL_ONLY 1
#else
#include <thread>
#endif

namespace meshwave {

// At most this many threads per call, whatever is asked.
inline constexpr int kMaxParallelThreads = 64;

// The threads a call should use: `requested` when positive (capped at
// kMaxParallelThreads), else the machine's hardware threads (at least 1).
// Always 1 in a WebAssembly build without threads.
inline int ResolveThreads(int requested) {
#ifdef MW_PARALLEL_SERIAL_ONLY
  (void)requested;
  return 1;
#else
  if (requested > 0) return std::min(requested, kMaxParallelThreads);
  const unsigned hardware = std::thread::hardware_concurrency();
  return std::clamp(static_cast<int>(hardware), 1, kMaxParallelThreads);
#endif
}

namespace parallel_internal {

// Runs work(worker) for worker in [0, workers): worker 0 on the calling
// thread, the others on new threads; rethrows the lowest worker's
// exception after all have joined.
template <class Work>
void RunWorkers(int workers, Work& work) {
  if (workers <= 1) {
    work(0);
    return;
  }
#ifdef MW_PARALLEL_SERIAL_ONLY
  for (int w = 0; w < workers; ++w) work(w);
#else
  std::vector<std::exception_ptr> errors(static_cast<size_t>(workers));
  std::vector<std::thread> threads;
  threads.reserve(static_cast<size_t>(workers - 1));
  for (int w = 1; w < workers; ++w) {
    threads.emplace_back([&work, &errors, w] {
      try {
        work(w);
      } catch (...) {
        errors[static_cast<size_t>(w)] = std::current_exception();
      }
    });
  }
  try {
    work(0);
  } catch (...) {
    errors[0] = std::current_exception();
  }
  for (std::thread& t : threads) t.join();
  for (const std::exception_ptr& e : errors) {
    if (e) std::rethrow_exception(e);
  }
#endif
}

}  // namespace parallel_internal

// body(begin, end) over contiguous chunks of [0, n), one chunk per thread,
// chunk i before chunk i + 1 in index order (chunk 0 on the calling
// thread). `threads` as ResolveThreads takes it; loops with fewer than
// `min_chunk` indices per thread use fewer threads (one below 2·min_chunk).
// With one thread: body(0, n) here. n == 0: body is not called.
template <class Body>
void ParallelFor(size_t n, int threads, Body&& body, size_t min_chunk = 4096) {
  if (n == 0) return;
  const size_t most = n / std::max<size_t>(min_chunk, 1);
  const size_t t = std::clamp<size_t>(
      std::min<size_t>(static_cast<size_t>(ResolveThreads(threads)), most), 1,
      kMaxParallelThreads);
  if (t == 1) {
    body(size_t{0}, n);
    return;
  }
  const size_t chunk = (n + t - 1) / t;
  auto work = [&](int w) {
    const size_t begin = std::min(n, static_cast<size_t>(w) * chunk);
    const size_t end = std::min(n, begin + chunk);
    if (begin < end) body(begin, end);
  };
  parallel_internal::RunWorkers(static_cast<int>(t), work);
}

// task(i) for every i in [0, count), taken in increasing order by up to
// `threads` workers as each finishes its last (good for tasks of uneven
// size: put the largest first). Which thread runs a task is not fixed, so
// tasks write only their own outputs. An exception skips the tasks above it
// not yet started; the lowest-numbered task's exception is rethrown.
template <class Task>
void ParallelTasks(size_t count, int threads, Task&& task) {
  if (count == 0) return;
  const int workers = static_cast<int>(
      std::min<size_t>(static_cast<size_t>(ResolveThreads(threads)), count));
  if (workers <= 1) {
    for (size_t i = 0; i < count; ++i) task(i);
    return;
  }
  std::atomic<size_t> next{0};
  std::atomic<size_t> first_failed{count};
  std::vector<std::exception_ptr> errors(count);
  auto work = [&](int) {
    for (size_t i = next++; i < count && i < first_failed.load(); i = next++) {
      try {
        task(i);
      } catch (...) {
        errors[i] = std::current_exception();
        size_t seen = first_failed.load();
        while (i < seen && !first_failed.compare_exchange_weak(seen, i)) {
        }
      }
    }
  };
  parallel_internal::RunWorkers(workers, work);
  for (const std::exception_ptr& e : errors) {
    if (e) std::rethrow_exception(e);
  }
}

// Runs every job, up to `threads` at once (the first on the calling
// thread); returns when all are done. One thread: in argument order. The
// first job's exception is preferred to the second's, and so on.
template <class... Jobs>
void ParallelInvoke(int threads, Jobs&&... jobs) {
  const std::function<void()> list[] = {std::function<void()>(std::ref(jobs))...};
  ParallelTasks(sizeof...(Jobs), threads, [&](size_t i) { list[i](); });
}

// std::sort(first, last) with its two halves sorted beside each other and
// then merged: the same sequence as std::sort wherever elements that
// compare equal are identical (pairs, integers; not records sorted by one
// field of several). Short ranges and one thread: std::sort here.
template <class RandomIt>
void ParallelSort(RandomIt first, RandomIt last, int threads) {
  const auto n = last - first;
  if (ResolveThreads(threads) < 2 || n < 2 * 65536) {
    std::sort(first, last);
    return;
  }
  const RandomIt middle = first + n / 2;
  ParallelInvoke(
      2, [&] { std::sort(first, middle); }, [&] { std::sort(middle, last); });
  std::inplace_merge(first, middle, last);
}

}  // namespace meshwave

#undef MW_PARALLEL_SERIAL_ONLY

#endif  // MESHWAVE_CORE_PARALLEL_FOR_H_
