#include "core/deferred.h"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace meshwave {
namespace {

TEST(DeferredSequenceTest, OnFirstUseBuildsOnlyAsFarAsAsked) {
  std::vector<size_t> built;
  DeferredSequence<std::string> values;
  values.Start(5, [&](size_t i) {
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

// A builder that throws at value 2: 0 and 1 stay usable, 2 and later
// rethrow, and nothing after 2 is built.
TEST(DeferredSequenceTest, AThrowingValueStopsTheSequenceThere) {
  std::atomic<int> calls{0};
  DeferredSequence<int> values;
  values.Start(5, [&](size_t i) {
    ++calls;
    if (i == 2) throw std::runtime_error("value 2");
    return static_cast<int>(i);
  });
  EXPECT_THROW(values.Get(4), std::runtime_error);
  EXPECT_THROW(values.Get(2), std::runtime_error);
  EXPECT_EQ(values.Get(1), 1);
  EXPECT_EQ(calls, 3);
}

TEST(DeferredSequenceTest, ManyReadersSeeTheSameValues) {
  {
    std::atomic<int> calls{0};
    DeferredSequence<std::vector<int>> values;
    values.Start(8, [&](size_t i) {
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
    EXPECT_EQ(calls, 8);  // each value built once
  }
}

}  // namespace
}  // namespace meshwave
