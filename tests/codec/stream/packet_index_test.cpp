#include "stream/packet_index.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "stream/distortion_index_writer.h"
#include "stream/stream_format_writer.h"


namespace meshwave {
namespace {

TEST(PacketIndexTest, CheckIsCrc16CcittFalse) {
  // The catalogue's check value of CRC-16/CCITT-FALSE.
  EXPECT_EQ(PacketCheck("123456789"), 0x29B1);
  EXPECT_EQ(PacketCheck(""), 0xFFFF);
}

TEST(PacketIndexTest, CheckCatchesEveryShortBurst) {
  std::mt19937 rng(7);
  std::string payload(3000, '\0');
  for (char& c : payload) c = static_cast<char>(rng());
  const uint16_t good = PacketCheck(payload);
  for (int trial = 0; trial < 2000; ++trial) {
    std::string bad = payload;
    const size_t bit = rng() % (8 * bad.size() - 16);
    const uint32_t burst = 1u | (rng() & 0x7fff) | 0x8000u;  // 16-bit burst
    for (int i = 0; i < 16; ++i) {
      if ((burst >> i) & 1) bad[(bit + i) / 8] ^= static_cast<char>(1 << ((bit + i) % 8));
    }
    EXPECT_NE(PacketCheck(bad), good) << trial;
  }
}

TEST(PacketIndexTest, DistortionCodeFollowsTheModelWithinItsStep) {
  // Two chains; chain 0's reductions shrink geometrically, chain 1 has a
  // negative reduction and a tail that reaches zero.
  DistortionModel model;
  model.base = 0.5;
  model.chain_start = {1000.0, 10.0};
  std::vector<double> truth = model.chain_start;
  double r = 600;
  for (int i = 0; i < 20; ++i) {
    model.chain.push_back(0);
    model.reduction.push_back(r);
    r *= 0.35;
  }
  for (double x : {6.0, -0.5, 3.0, 1.5}) {
    model.chain.push_back(1);
    model.reduction.push_back(x);
  }
  proto::StreamHeader written;
  const double scale = 2.0;
  WriteDistortionIndex(model, scale * (0.5 + 1010.0), written);
  auto header = ToStreamHeader(written);
  ASSERT_TRUE(header.ok());
  EXPECT_DOUBLE_EQ(header->base_distortion, scale * 0.5);
  ASSERT_EQ(header->packets.distortion_step.size(), model.reduction.size());
  const DistortionEstimates e = ReadDistortionIndex(*header, model.chain);
  EXPECT_NEAR(e.start(), scale * 1010.5, 1e-3);
  double left = e.start();
  std::vector<double> chains = truth;
  const double tolerance = std::exp2(1.0 / 64) - 1 + 1e-6;
  for (size_t i = 0; i < model.reduction.size(); ++i) {
    left -= e.reduction[i];
    chains[model.chain[i]] -= model.reduction[i];
    const double truth_left = scale * (model.base + chains[0] + chains[1]);
    if (chains[model.chain[i]] > 1e-9 * truth[model.chain[i]]) {
      EXPECT_NEAR(left, truth_left, tolerance * truth_left) << i;
    }
  }
  EXPECT_NEAR(left, scale * (model.base + chains[0]), tolerance * left);
  // The estimate from the chains' last terms: the same figure, whatever the
  // order in which the chains' packets interleave.
  std::vector<double> now = e.chain_start;
  for (size_t i = 0; i < model.reduction.size(); ++i) now[model.chain[i]] = e.after[i];
  EXPECT_NEAR(e.Estimate(now), left, 1e-9 * left);
}

}  // namespace
}  // namespace meshwave
