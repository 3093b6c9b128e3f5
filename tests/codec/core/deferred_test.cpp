#include "core/deferred.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace meshwave {
namespace {

TEST(DeferredSequenceTest, OnFirstUseBuildsOnlyAsFarAsAsked) {
  std::vector<size_t> built;
  DeferredSequence<std::string> values;
  values.Start(false, 5, [&](size_t i) {
    built.push_back(i);
    return std::string(i + 1, 'x');
  });
  EXPECT_TRUE(built.empty());
  EXPECT_EQ(values.Get(2), "xxx");
  EXPECT_EQ(built, (std::vector<size_t>{0, 1, 2}));  // in order, and no further
  EXPECT_EQ(values.Get(0), "x");
  EXPECT_EQ(values.Get(4), "xxxxx");
  EXPECT_EQ(built, (std::vector<size_t>{0, 1, 2, 3, 4}));  // each once
}

// Get(i) waits for value i only: with the builder held back before value 2,
// values 0 and 1 are already there.
TEST(DeferredSequenceTest, InTheBackgroundGetWaitsOnlyForItsValue) {
  std::atomic<bool> release{false};
  std::thread::id built_on;
  DeferredSequence<int> values;
  values.Start(true, 4, [&](size_t i) {
    built_on = std::this_thread::get_id();
    while (i == 2 && !release) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    return static_cast<int>(10 * i);
  });
  EXPECT_EQ(values.Get(1), 10);
  EXPECT_EQ(values.Get(0), 0);
  EXPECT_NE(built_on, std::this_thread::get_id());
  release = true;
  EXPECT_EQ(values.Get(3), 30);
  EXPECT_EQ(values.Get(2), 20);
}

// A builder that throws at value 2: 0 and 1 stay usable, 2 and later
// rethrow, and nothing after 2 is built. Both ways of building.
TEST(DeferredSequenceTest, AThrowingValueStopsTheSequenceThere) {
  for (bool background : {false, true}) {
    std::atomic<int> calls{0};
    DeferredSequence<int> values;
    values.Start(background, 5, [&](size_t i) {
      ++calls;
      if (i == 2) throw std::runtime_error("value 2");
      return static_cast<int>(i);
    });
    EXPECT_THROW(values.Get(4), std::runtime_error) << background;
    EXPECT_THROW(values.Get(2), std::runtime_error) << background;
    EXPECT_EQ(values.Get(1), 1) << background;
    EXPECT_EQ(calls, 3) << background;
  }
}

TEST(DeferredSequenceTest, ManyReadersSeeTheSameValues) {
  for (bool background : {false, true}) {
    std::atomic<int> calls{0};
    DeferredSequence<std::vector<int>> values;
    values.Start(background, 8, [&](size_t i) {
      ++calls;
      return std::vector<int>(1000, static_cast<int>(i));
    });
    std::vector<std::thread> readers;
    std::atomic<int> wrong{0};
    for (int t = 0; t < 4; ++t) {
      readers.emplace_back([&, t] {
        for (size_t i = 0; i < 8; ++i) {
          const size_t k = (i + static_cast<size_t>(t)) % 8;
          if (values.Get(k)[999] != static_cast<int>(k)) ++wrong;
        }
      });
    }
    for (auto& r : readers) r.join();
    EXPECT_EQ(wrong, 0);
    EXPECT_EQ(calls, 8) << background;  // each value built once
  }
}

// Destroyed while its builder runs: the builder stops after the value it
// is building instead of building the rest.
TEST(DeferredSequenceTest, DestroyedDuringTheBuildStopsTheBuilder) {
  std::atomic<int> calls{0};
  std::atomic<bool> started{false};
  {
    DeferredSequence<int> values;
    values.Start(true, 1000, [&](size_t i) {
      ++calls;
      started = true;
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      return static_cast<int>(i);
    });
    while (!started) std::this_thread::yield();
  }
  EXPECT_LT(calls, 1000);
  EXPECT_GE(calls, 1);
}

}  // namespace
}  // namespace meshwave
