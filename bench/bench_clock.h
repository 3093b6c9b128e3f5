// Timing helpers shared by the benchmark programs that are not Google
// Benchmark ones: the calling thread's CPU time, and a median of runs.
#ifndef MESHWAVE_BENCH_BENCH_CLOCK_H_
#define MESHWAVE_BENCH_BENCH_CLOCK_H_

#include <time.h>

#include <algorithm>
#include <vector>

namespace meshwave::bench {

inline double ThreadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
}

// The upper median of `v` (0 when empty).
inline double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

}  // namespace meshwave::bench

#endif  // MESHWAVE_BENCH_BENCH_CLOCK_H_
