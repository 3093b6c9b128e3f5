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

TEST(DeferredTest, OnFirstUseBuildsOnceOnTheCallersThread) {
  int builds = 0;
  std::thread::id built_on;
  Deferred<std::string> value;
  value.Start(false, [&] {
    ++builds;
    built_on = std::this_thread::get_id();
    return std::string("mesh");
  });
  EXPECT_EQ(builds, 0);  // nothing before the first use
  EXPECT_EQ(value.Get(), "mesh");
  EXPECT_EQ(value.Get(), "mesh");
  EXPECT_EQ(builds, 1);
  EXPECT_EQ(built_on, std::this_thread::get_id());
}

TEST(DeferredTest, InTheBackgroundBuildsOnAnotherThread) {
  std::atomic<int> builds = 0;
  std::thread::id built_on;
  Deferred<std::vector<int>> value;
  value.Start(true, [&] {
    ++builds;
    built_on = std::this_thread::get_id();
    return std::vector<int>(1000, 7);
  });
  EXPECT_EQ(value.Get().size(), 1000u);
  EXPECT_EQ(builds, 1);
  EXPECT_NE(built_on, std::this_thread::get_id());
  value.Get().push_back(8);  // the value is the object's own
  EXPECT_EQ(value.Get().size(), 1001u);
}

TEST(DeferredTest, ManyThreadsGetTheOneValue) {
  for (bool background : {false, true}) {
    std::atomic<int> builds = 0;
    Deferred<int> value;
    value.Start(background, [&] { return ++builds * 42; });
    std::vector<std::thread> readers;
    std::atomic<int> wrong = 0;
    for (int i = 0; i < 4; ++i) {
      readers.emplace_back([&] {
        if (value.Get() != 42) ++wrong;
      });
    }
    for (auto& t : readers) t.join();
    EXPECT_EQ(builds, 1) << background;
    EXPECT_EQ(wrong, 0) << background;
  }
}

TEST(DeferredTest, WhatTheBuilderThrewIsRethrownOnEveryGet) {
  for (bool background : {false, true}) {
    Deferred<int> value;
    value.Start(background, []() -> int { throw std::runtime_error("no memory"); });
    for (int i = 0; i < 2; ++i) {
      try {
        value.Get();
        ADD_FAILURE() << "no exception";
      } catch (const std::runtime_error& e) {
        EXPECT_STREQ(e.what(), "no memory");
      }
    }
  }
}

TEST(DeferredTest, DestroyedBeforeUseWaitsForItsThread) {
  std::atomic<bool> done = false;
  {
    Deferred<int> value;
    value.Start(true, [&] {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      done = true;
      return 1;
    });
  }
  EXPECT_TRUE(done);
}

}  // namespace
}  // namespace meshwave
