// HeldUnits (meshwave/held_units.h): the unit and part dependency rules of
// docs/FORMAT.md section 6, on a header made by hand so that every rule
// has a case of its own. The decoder keeps its held set in one: that
// ProgressiveDecoder follows these rules on real streams is in
// progressive_decoder_test.cpp and precinct_stream_test.cpp.
#include "meshwave/held_units.h"

#include <gtest/gtest.h>

namespace meshwave {
namespace {

constexpr uint32_t kWhole = StreamUnit::kWholePacket;

// Two subbands of two bitplanes each and one base refinement plane:
// packets 0 = (0, 1), 1 = (0, 0), 2 = (1, 1), 3 = (1, 0), 4 = base plane 0.
// The lowest bitplane of each subband is split: packet 1 into subband 0's
// two precincts, packet 3 into subband 1's three, whose parents are
// precincts 0, 0 and 1 of subband 0.
StreamHeader TwoSubbands(StreamCoder coder) {
  StreamHeader h;
  h.coder = coder;
  h.transform.levels = 2;
  h.quantizers.assign(6, StreamHeader::Quantizer{1.0, 0, 1});
  h.base.refinement_planes = 1;
  h.packets.split_planes = {1, 1};
  return h;
}

HeldUnits TwoSubbandUnits(StreamCoder coder = StreamCoder::k3xC) {
  return HeldUnits(TwoSubbands(coder), PrecinctParents{{0, 0}, {0, 0, 1}});
}

TEST(HeldUnitsTest, SplitPacketsHaveOnePartPerPrecinct) {
  const HeldUnits u = TwoSubbandUnits();
  EXPECT_EQ(u.packet_count(), 5u);
  const uint32_t parts[] = {0, 2, 0, 3, 0};
  for (uint32_t id = 0; id < 5; ++id) EXPECT_EQ(u.PartCount(id), parts[id]) << id;
  EXPECT_EQ(u.PartCount(5), 0u);
}

TEST(HeldUnitsTest, RefusesUnitsNotInTheStream) {
  HeldUnits u = TwoSubbandUnits();
  EXPECT_TRUE(u.Valid({3, 2}));
  EXPECT_FALSE(u.Valid({3, 3}));     // subband 1 has three precincts
  EXPECT_FALSE(u.Valid({0, 0}));     // packet 0 is not split
  EXPECT_FALSE(u.Valid({5, kWhole}));
  EXPECT_FALSE(u.Ready({5, kWhole}));
  EXPECT_EQ(u.FirstMissing({5, kWhole}), -1);
  u.Add({3, 3});  // ignored
  EXPECT_FALSE(u.Has({3, kWhole}));
}

TEST(HeldUnitsTest, APacketNeedsTheOneAboveAndItsParentWhole) {
  HeldUnits u = TwoSubbandUnits();
  EXPECT_TRUE(u.Ready({0, kWhole}));
  EXPECT_TRUE(u.Ready({4, kWhole}));  // the base refinement's top plane
  EXPECT_EQ(u.FirstMissing({1, kWhole}), 0);
  EXPECT_EQ(u.FirstMissing({2, kWhole}), 0);  // its parent subband's, 3xC
  u.Add({0, kWhole});
  EXPECT_TRUE(u.Ready({1, kWhole}));
  EXPECT_TRUE(u.Ready({2, kWhole}));
  u.Add({2, kWhole});
  // Packet 3 needs packet 2 above it and packet 1, its parent, whole: one
  // part of packet 1 is not enough.
  EXPECT_EQ(u.FirstMissing({3, kWhole}), 1);
  u.Add({1, 0});
  EXPECT_EQ(u.FirstMissing({3, kWhole}), 1);
  u.Add({1, 1});
  EXPECT_TRUE(u.Has({1, kWhole}));  // every part: the packet whole
  EXPECT_TRUE(u.Ready({3, kWhole}));
}

TEST(HeldUnitsTest, APartNeedsItsPrecinctsShares) {
  HeldUnits u = TwoSubbandUnits();
  u.Add({0, kWhole});
  // Part 2 of packet 3: packet 2 first (above it, not split), then its
  // parent precinct's share of packet 1, precinct 1.
  EXPECT_EQ(u.FirstMissing({3, 2}), 2);
  u.Add({2, kWhole});
  EXPECT_EQ(u.FirstMissing({3, 2}), 1);
  u.Add({1, 0});
  EXPECT_FALSE(u.Ready({3, 2}));
  EXPECT_TRUE(u.Ready({3, 0}));  // its parent precinct is 0
  EXPECT_TRUE(u.Ready({3, 1}));
  u.Add({1, 1});
  EXPECT_TRUE(u.Ready({3, 2}));
  EXPECT_FALSE(u.Ready({1, 1}));  // held
  EXPECT_TRUE(u.DependenciesMet({1, 1}));
}

TEST(HeldUnitsTest, AWholePacketHoldsAllItsParts) {
  HeldUnits u = TwoSubbandUnits();
  u.Add({0, kWhole});
  u.Add({1, kWhole});
  EXPECT_TRUE(u.Has({1, 0}));
  EXPECT_TRUE(u.Has({1, 1}));
  EXPECT_FALSE(u.Ready({1, 0}));
}

TEST(HeldUnitsTest, SimHasNoParentDependency) {
  HeldUnits u = TwoSubbandUnits(StreamCoder::kSim);
  EXPECT_TRUE(u.Ready({2, kWhole}));
  u.Add({2, kWhole});
  EXPECT_TRUE(u.Ready({3, 2}));
  EXPECT_FALSE(u.Ready({1, 0}));  // packet 0 above it
}

TEST(HeldUnitsTest, ClearHoldsNothing) {
  HeldUnits u = TwoSubbandUnits();
  u.Add({0, kWhole});
  u.Add({1, 1});
  u.Clear();
  EXPECT_FALSE(u.Has({0, kWhole}));
  EXPECT_FALSE(u.Has({1, 1}));
  EXPECT_TRUE(u.Ready({0, kWhole}));
}

}  // namespace
}  // namespace meshwave
