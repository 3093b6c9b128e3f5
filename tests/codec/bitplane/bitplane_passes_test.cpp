#include "bitplane/bitplane_passes.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "bitplane/decoder_io.h"
#include "bitplane/encoder_io.h"
#include "bitplane/subband_layout.h"
#include "codec/hierarchy_on_grid_testonly.h"
#include "codec/test_meshes.h"

namespace meshwave {
namespace {

// One subband coded bitplane by bitplane, as the stream codes a component:
// the finest subband of a four-level hierarchy over the icosahedron (1,920
// coefficients), its magnitudes a smooth field over the coefficients'
// positions, so that significant coefficients come in patches, as details
// of a real surface do.
struct SmoothSubband {
  SubbandLayout layout;
  std::vector<uint32_t> q0;  // Morton order
  std::vector<uint8_t> negative;
  int top = -1;
};

SmoothSubband MakeSmoothSubband() {
  const testing::HierarchyOnGrid ico =
      testing::BuildHierarchyOnGrid(testing::Icosahedron(), 4, Vec3::Constant(1000));
  const int j = 3;
  auto layouts = BuildSubbandLayouts(*ico.h, ico.grid, 32);
  const auto positions = ReferencePositions(*ico.h, ico.grid)[j];
  SmoothSubband s{std::move(layouts[j][0]), {}, {}, -1};
  const double scale = 1000.0 * std::ldexp(1.0, j + 1);
  std::vector<uint32_t> q0(positions.size());
  std::vector<uint8_t> negative(positions.size());
  std::mt19937 rng(11);
  for (size_t k = 0; k < positions.size(); ++k) {
    const double x = positions[k][0] / scale, y = positions[k][1] / scale,
                 z = positions[k][2] / scale;
    const double field = std::sin(5 * x + 1) * std::sin(4 * y) * std::cos(3 * z + 0.5);
    q0[k] = static_cast<uint32_t>(std::max(0.0, 300 * field - 40));
    negative[k] = q0[k] != 0 && (rng() & 1);
  }
  s.q0 = InMortonOrder<uint32_t>(s.layout, q0);
  s.negative = InMortonOrder<uint8_t>(s.layout, negative);
  uint32_t largest = 0;
  for (uint32_t v : q0) largest = std::max(largest, v);
  s.top = std::bit_width(largest) - 1;
  return s;
}

// Codes every bitplane of `s` (with neighbour contexts or not), decodes the
// packets back and checks that the decoder ends with the encoder's values.
// Returns the packets' total bytes.
size_t CodeAndDecodeEveryBitplane(const SmoothSubband& s, bool neighbours) {
  ContextSources sources;
  if (neighbours) sources.neighbour_position = s.layout.neighbour_position;
  ComponentState enc_state;
  enc_state.Init(s.layout.tree, s.top);
  std::vector<std::string> packets;
  for (int b = s.top; b >= 0; --b) {
    ArithmeticEncoder enc;
    ComponentContexts contexts;
    EncoderIo io(enc, s.q0, s.negative);
    CodeBitplane(s.layout.tree, enc_state, b, sources, contexts, io);
    packets.push_back(enc.Finish());
  }
  ComponentState dec_state;
  dec_state.Init(s.layout.tree, s.top);
  size_t bytes = 0;
  for (int b = s.top; b >= 0; --b) {
    const std::string& packet = packets[static_cast<size_t>(s.top - b)];
    bytes += packet.size();
    ComponentContexts contexts;
    DecoderIo io(packet);
    CodeBitplane(s.layout.tree, dec_state, b, sources, contexts, io);
    EXPECT_FALSE(io.decoder().overrun()) << "bitplane " << b;
  }
  EXPECT_EQ(dec_state.mag, s.q0);
  for (size_t i = 0; i < s.layout.size(); ++i) {
    if (s.q0[i] != 0) {
      EXPECT_EQ(dec_state.negative[i], s.negative[i]) << i;
    }
  }
  return bytes;
}

TEST(BitplanePassesTest, EveryBitplaneDecodesToTheEncodersValues) {
  const SmoothSubband s = MakeSmoothSubband();
  ASSERT_GE(s.top, 6);
  size_t significant = 0;
  for (uint32_t v : s.q0) significant += v != 0;
  // Neither empty nor full: there is a significance map to code.
  ASSERT_GT(significant, s.q0.size() / 8);
  ASSERT_LT(significant, s.q0.size() * 7 / 8);
  EXPECT_GT(CodeAndDecodeEveryBitplane(s, /*neighbours=*/false), 0u);
}

// 3xC's neighbour count (nctx): on a field whose significant coefficients
// come in patches, knowing how many neighbours are significant already
// makes the significance symbols cheaper.
TEST(BitplanePassesTest, NeighbourContextsMakeAPatchySignificanceMapCheaper) {
  const SmoothSubband s = MakeSmoothSubband();
  const size_t without = CodeAndDecodeEveryBitplane(s, /*neighbours=*/false);
  const size_t with = CodeAndDecodeEveryBitplane(s, /*neighbours=*/true);
  EXPECT_LT(static_cast<double>(with), 0.97 * static_cast<double>(without))
      << with << " bytes with neighbour contexts, " << without << " without";
}

}  // namespace
}  // namespace meshwave
