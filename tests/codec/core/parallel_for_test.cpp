#include "core/parallel_for.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace meshwave {
namespace {

TEST(ParallelForTest, ResolveThreadsTakesAPositiveRequestAndZeroAsTheCores) {
  EXPECT_EQ(ResolveThreads(1), 1);
  EXPECT_EQ(ResolveThreads(3), 3);
  EXPECT_EQ(ResolveThreads(1000), kMaxParallelThreads);
  const int cores = ResolveThreads(0);
  EXPECT_GE(cores, 1);
  EXPECT_LE(cores, kMaxParallelThreads);
  EXPECT_EQ(ResolveThreads(-1), cores);
}

TEST(ParallelForTest, CoversEveryIndexOnceInContiguousChunks) {
  for (int threads : {1, 2, 3, 7}) {
    for (size_t n : {size_t{0}, size_t{1}, size_t{5}, size_t{1000}, size_t{1001}}) {
      std::vector<int> seen(n, 0);
      std::atomic<size_t> calls{0};
      ParallelFor(
          n, threads,
          [&](size_t begin, size_t end) {
            ASSERT_LT(begin, end);
            ++calls;
            for (size_t i = begin; i < end; ++i) ++seen[i];
          },
          /*min_chunk=*/1);
      for (size_t i = 0; i < n; ++i) ASSERT_EQ(seen[i], 1) << "n " << n << " index " << i;
      EXPECT_LE(calls.load(), static_cast<size_t>(threads));
      if (n == 0) {
        EXPECT_EQ(calls.load(), 0u);
      }
    }
  }
}

TEST(ParallelForTest, SumsInChunksCombinedInOrderMatchTheSerialLoop) {
  std::vector<double> values(100000);
  for (size_t i = 0; i < values.size(); ++i) values[i] = 1.0 / static_cast<double>(i + 1);
  const auto sum = [&](int threads) {
    std::vector<double> per_index(values.size());
    ParallelFor(values.size(), threads, [&](size_t begin, size_t end) {
      for (size_t i = begin; i < end; ++i) per_index[i] = values[i] * values[i];
    });
    return std::accumulate(per_index.begin(), per_index.end(), 0.0);
  };
  const double serial = sum(1);
  EXPECT_EQ(sum(2), serial);
  EXPECT_EQ(sum(3), serial);
}

TEST(ParallelForTest, OneThreadRunsTheWholeLoopOnTheCallingThread) {
  const std::thread::id caller = std::this_thread::get_id();
  int calls = 0;
  ParallelFor(
      100000, 1,
      [&](size_t begin, size_t end) {
        EXPECT_EQ(std::this_thread::get_id(), caller);
        EXPECT_EQ(begin, 0u);
        EXPECT_EQ(end, 100000u);
        ++calls;
      },
      1);
  EXPECT_EQ(calls, 1);
  std::vector<size_t> order;
  ParallelTasks(5, 1, [&](size_t i) {
    EXPECT_EQ(std::this_thread::get_id(), caller);
    order.push_back(i);
  });
  EXPECT_EQ(order, (std::vector<size_t>{0, 1, 2, 3, 4}));
  std::string trace;
  ParallelInvoke(
      1, [&] { trace += "a"; }, [&] { trace += "b"; }, [&] { trace += "c"; });
  EXPECT_EQ(trace, "abc");
}

TEST(ParallelForTest, ShortLoopsStayOnTheCallingThread) {
  const std::thread::id caller = std::this_thread::get_id();
  ParallelFor(8000, 4, [&](size_t begin, size_t end) {
    EXPECT_EQ(std::this_thread::get_id(), caller);
    EXPECT_EQ(end - begin, 8000u);
  });  // min_chunk 4096: fewer than two chunks' worth
}

TEST(ParallelForTest, RethrowsTheLowestChunksExceptionOnTheCaller) {
  for (int threads : {1, 2, 4}) {
    std::atomic<size_t> done{0};
    try {
      ParallelFor(
          4000, threads,
          [&](size_t begin, size_t end) {
            for (size_t i = begin; i < end; ++i) {
              if (i == 3500 || i == 2100) throw std::runtime_error("index " + std::to_string(i));
              ++done;
            }
          },
          1);
      FAIL() << "no exception with " << threads << " threads";
    } catch (const std::runtime_error& e) {
      // Serial: the first index that throws; in chunks of 1000 or 2000 the
      // chunk holding 2100 comes first as well.
      EXPECT_STREQ(e.what(), "index 2100") << threads << " threads";
    }
    EXPECT_LT(done.load(), 4000u);
  }
}

TEST(ParallelForTest, TasksRunOnceEachAndTheLowestExceptionWins) {
  for (int threads : {1, 2, 3}) {
    std::vector<std::atomic<int>> runs(50);
    ParallelTasks(runs.size(), threads, [&](size_t i) { ++runs[i]; });
    for (auto& r : runs) EXPECT_EQ(r.load(), 1);

    try {
      ParallelTasks(10, threads, [&](size_t i) {
        if (i == 2) throw std::invalid_argument("two");
        if (i == 3) throw std::invalid_argument("three");
      });
      FAIL() << "no exception with " << threads << " threads";
    } catch (const std::invalid_argument& e) {
      // Task 3 may or may not run; 2 always does, and wins.
      EXPECT_STREQ(e.what(), "two");
    }
  }
}

TEST(ParallelForTest, ParallelSortGivesStdSortsSequence) {
  std::vector<std::pair<uint64_t, uint32_t>> pairs(300001);
  uint64_t x = 12345;
  for (size_t i = 0; i < pairs.size(); ++i) {
    x = x * 6364136223846793005ULL + 1442695040888963407ULL;
    pairs[i] = {x >> 50, static_cast<uint32_t>(x >> 20) % 7};  // many equal pairs
  }
  auto expected = pairs;
  std::sort(expected.begin(), expected.end());
  for (int threads : {1, 2, 3}) {
    auto sorted = pairs;
    ParallelSort(sorted.begin(), sorted.end(), threads);
    EXPECT_EQ(sorted, expected) << threads << " threads";
  }
}

TEST(ParallelForTest, InvokeRunsEveryJobAndRethrowsItsException) {
  for (int threads : {0, 1, 2, 3}) {
    std::atomic<int> a{0}, b{0}, c{0};
    ParallelInvoke(
        threads, [&] { ++a; }, [&] { ++b; }, [&] { ++c; });
    EXPECT_EQ(a + b + c, 3);
    EXPECT_EQ(a * b * c, 1);
    std::atomic<bool> first_ran{false};
    EXPECT_THROW(ParallelInvoke(
                     threads, [&] { first_ran = true; },
                     [] { throw std::out_of_range("second"); }),
                 std::out_of_range);
    EXPECT_TRUE(first_ran.load());  // jobs before the one that threw still run
  }
}

}  // namespace
}  // namespace meshwave
