#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <type_traits>

#include "entropy/context_model.h"

namespace meshwave {
namespace {

TEST(BinaryContextTest, StartsAtOneHalf) {
  EXPECT_EQ(BinaryContext().probability(), 16384u);
}

TEST(BinaryContextTest, FirstUpdatesFollowTheFormulaOfTheFormat) {
  // p = 32768, r(0) = 65535 / 2 = 32767: p += (32768 * 32767) >> 16.
  BinaryContext ctx;
  ctx.Update(0);
  EXPECT_EQ(ctx.probability(), (32768u + 16383u) >> 1);
  // r(1) = 65535 / 3 = 21845: p -= (49151 * 21845) >> 16 = 16383.
  ctx.Update(1);
  EXPECT_EQ(ctx.probability(), (49151u - 16383u) >> 1);
}

// A context given a start (3xC's neighbour contexts, FORMAT.md 5.3) holds
// its estimate and adapts at the rate of the symbols it counts as seen.
TEST(BinaryContextTest, AStartedContextAdaptsAsIfItHadSeenItsCount) {
  BinaryContext ctx(52429, 2);
  EXPECT_EQ(ctx.probability(), 52429u >> 1);
  // r(2) = 65535 / 4 = 16383: p -= (52429 * 16383) >> 16 = 13106.
  ctx.Update(1);
  EXPECT_EQ(ctx.probability(), (52429u - 13106u) >> 1);
  // r(3) = 65535 / 5 = 13107: p += ((65536 - 39323) * 13107) >> 16 = 5242.
  ctx.Update(0);
  EXPECT_EQ(ctx.probability(), (39323u + 5242u) >> 1);
}

TEST(BinaryContextTest, ProbabilityStaysInsideTheCoderRange) {
  for (int bit = 0; bit <= 1; ++bit) {
    BinaryContext ctx;
    for (int i = 0; i < 1000000; ++i) ctx.Update(bit);
    EXPECT_GE(ctx.probability(), 1u);
    EXPECT_LE(ctx.probability(), 32767u);
    // ... and saturates where the 1/32 rate stops moving a 16-bit estimate.
    EXPECT_EQ(bit == 0 ? 32768 - ctx.probability() : ctx.probability(), 16u);
  }
  std::mt19937_64 rng(5);
  BinaryContext ctx;
  for (int i = 0; i < 1000000; ++i) {
    ctx.Update(static_cast<int>(rng() % 2));
    ASSERT_GE(ctx.probability(), 1u);
    ASSERT_LE(ctx.probability(), 32767u);
  }
}

// Fixed-rate estimators the context model was chosen against: 16-bit state
// moved by 2^-shift, or the mean of two such; LZMA's 11-bit state, shift 5.
class ShiftEstimator {
 public:
  ShiftEstimator(int bits, int shift) : bits_(bits), shift_(shift) {
    p_ = 1u << (bits - 1);
  }
  uint32_t probability15() const { return p_ << 15 >> bits_; }
  void Update(int bit) {
    if (bit == 0) {
      p_ += ((1u << bits_) - p_) >> shift_;
    } else {
      p_ -= p_ >> shift_;
    }
  }

 private:
  int bits_;
  int shift_;
  uint32_t p_;
};

// Learning cost of an estimator `Model`: the ideal code length in bits of
// one context's `count` symbols minus what the true P(1) would cost, mean
// over streams whose P(1) `draw_p1` picks.
template <class Model, class MakeModel, class DrawP1>
double MeanExcessBits(MakeModel make, DrawP1 draw_p1, int count) {
  std::mt19937_64 rng(count);
  std::uniform_real_distribution<double> unit(0, 1);
  double excess = 0;
  constexpr int kStreams = 4000;
  for (int s = 0; s < kStreams; ++s) {
    const double p1 = draw_p1(rng);
    Model model = make();
    for (int i = 0; i < count; ++i) {
      const int bit = unit(rng) < p1 ? 1 : 0;
      double q0;
      if constexpr (std::is_same_v<Model, BinaryContext>) {
        q0 = model.probability() / 32768.0;
      } else {
        q0 = model.probability15() / 32768.0;
      }
      excess -= std::log2(bit == 0 ? q0 : 1 - q0);
      excess += std::log2(bit == 0 ? 1 - p1 : p1);
      model.Update(bit);
    }
  }
  return excess / kStreams;
}

struct DualShiftEstimator {
  ShiftEstimator fast{16, 4};
  ShiftEstimator slow{16, 7};
  uint32_t probability15() const {
    return (fast.probability15() + slow.probability15()) >> 1;
  }
  void Update(int bit) {
    fast.Update(bit);
    slow.Update(bit);
  }
};

// The evidence behind the adaptation rule (context_model.h): on packets of
// 30 and 300 symbols per context the count-based start costs at least 20%
// fewer bits over the entropy than shift 4, LZMA's shift 5 and the average
// of shifts 4 and 7 (the first rows of the table there).
TEST(BinaryContextTest, LearnsSmallPacketsFasterThanFixedShiftEstimators) {
  auto uniform = [](std::mt19937_64& rng) {
    return std::uniform_real_distribution<double>(0, 1)(rng);
  };
  auto skewed = [](std::mt19937_64& rng) {
    std::uniform_real_distribution<double> unit(0, 1);
    const double p = std::pow(10.0, -3 + 2.7 * unit(rng));
    return rng() % 2 ? p : 1 - p;
  };
  for (int count : {30, 300}) {
    for (int source = 0; source < 2; ++source) {
      auto run = [&](auto make) {
        using Model = decltype(make());
        return source == 0 ? MeanExcessBits<Model>(make, uniform, count)
                           : MeanExcessBits<Model>(make, skewed, count);
      };
      const double ours = run([] { return BinaryContext(); });
      const double shift4 = run([] { return ShiftEstimator(16, 4); });
      const double lzma = run([] { return ShiftEstimator(11, 5); });
      const double dual = run([] { return DualShiftEstimator(); });
      SCOPED_TRACE(testing::Message()
                   << "count " << count << " source " << source << ": ours "
                   << ours << " shift4 " << shift4 << " lzma " << lzma
                   << " dual " << dual);
      EXPECT_LT(ours, 0.8 * shift4);
      EXPECT_LT(ours, 0.8 * lzma);
      EXPECT_LT(ours, 0.8 * dual);
    }
  }
}

}  // namespace
}  // namespace meshwave
