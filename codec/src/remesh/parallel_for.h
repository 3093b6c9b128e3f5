// Runs a loop body over [0, n) split into contiguous chunks on a few
// std::threads. Bodies must only write state owned by their own indices, so
// results do not depend on the thread count.
#ifndef MESHWAVE_REMESH_PARALLEL_FOR_H_
#define MESHWAVE_REMESH_PARALLEL_FOR_H_

#include <algorithm>
#include <cstddef>
#include <thread>
#include <vector>

namespace meshwave::remesh {

// body(begin, end) for chunks of [0, n). Loops shorter than `min_chunk`
// per thread run on the calling thread alone (spawning costs ~50 µs).
template <class Body>
void ParallelFor(size_t n, int threads, Body&& body, size_t min_chunk = 4096) {
  const size_t t = std::clamp<size_t>(
      std::min<size_t>(static_cast<size_t>(std::max(threads, 1)),
                       n / std::max<size_t>(min_chunk, 1)),
      1, 64);
  if (t <= 1) {
    body(size_t{0}, n);
    return;
  }
  std::vector<std::thread> workers;
  workers.reserve(t - 1);
  const size_t chunk = (n + t - 1) / t;
  for (size_t i = 1; i < t; ++i) {
    const size_t begin = std::min(n, i * chunk);
    const size_t end = std::min(n, begin + chunk);
    workers.emplace_back([&body, begin, end] { body(begin, end); });
  }
  body(size_t{0}, std::min(n, chunk));
  for (std::thread& w : workers) w.join();
}

}  // namespace meshwave::remesh

#endif  // MESHWAVE_REMESH_PARALLEL_FOR_H_
