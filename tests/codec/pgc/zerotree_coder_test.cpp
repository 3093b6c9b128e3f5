#include "pgc/zerotree_coder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "codec/stream/stream_test_util.h"
#include "codec/test_meshes.h"
#include "meshwave/mesh_stats.h"
#include "meshwave/progressive_decoder.h"
#include "meshwave/subdivision.h"
#include "pgc/pgc_stream.h"
#include "stream/packet_index.h"

namespace meshwave {
namespace {

using testing::BumpySphere;
using testing::Octahedron;
using testing::OpenPatch;
using testing::Psnr;

struct Fixture {
  SemiRegularMesh mesh;
  PgcStream stream;
  double diag = 0;
};

const Fixture& Encoded() {
  static const Fixture* fixture = [] {
    auto* f = new Fixture;
    auto s = EncodePgc(BumpySphere(4), testing::EqualStepOptions());
    EXPECT_TRUE(s.ok()) << s.status().ToString();
    f->stream = *std::move(s);
    // In the order the decoder returns the vertices.
    f->mesh = f->stream.mesh;
    f->diag = BoundingBox(f->mesh.positions).Diagonal();
    return f;
  }();
  return *fixture;
}

std::unique_ptr<PgcDecoder> NewDecoder(const PgcStream& s) {
  auto d = PgcDecoder::Create(s.header);
  EXPECT_TRUE(d.ok()) << d.status().ToString();
  return std::move(d).value();
}

// Decodes `count` packets, each from its own allocation (so ASan sees any
// read past a packet), and returns the positions.
std::vector<Vec3> DecodePrefix(const PgcStream& s, size_t count) {
  auto d = NewDecoder(s);
  for (size_t i = 0; i < count; ++i) {
    const std::vector<char> copy(s.packets[i].begin(), s.packets[i].end());
    const Status status = d->AddPacket(std::string_view(copy.data(), copy.size()));
    EXPECT_TRUE(status.ok()) << i << ": " << status.ToString();
  }
  return d->Positions();
}

TEST(ZerotreeCoderTest, UsesTheQuantizersAndVertexOrderOfEncodeMesh) {
  const Fixture& f = Encoded();
  auto sim = EncodeMesh(BumpySphere(4), testing::EqualStepOptions());
  ASSERT_TRUE(sim.ok());
  EXPECT_EQ(f.stream.mesh.positions, sim->mesh.positions);
  const auto& a = f.stream.header;
  const auto& b = sim->header;
  ASSERT_EQ(a.quantizers.size(), b.quantizers.size());
  for (size_t i = 0; i < a.quantizers.size(); ++i) {
    EXPECT_EQ(a.quantizers[i].step, b.quantizers[i].step) << i;
    EXPECT_EQ(a.quantizers[i].top_bitplane, b.quantizers[i].top_bitplane) << i;
    EXPECT_EQ(a.quantizers[i].deadzone, b.quantizers[i].deadzone) << i;
  }
  EXPECT_EQ(a.base.vertex_count, b.base.vertex_count);
  EXPECT_EQ(a.base.face_count, b.base.face_count);
  EXPECT_EQ(a.base.origin, b.base.origin);
  EXPECT_EQ(a.base.step, b.base.step);
  EXPECT_EQ(a.base.coded, b.base.coded);
  EXPECT_NEAR(a.base_distortion, b.base_distortion, 1e-9 * a.base_distortion);
}

TEST(ZerotreeCoderTest, HasOnePacketPerBitplane) {
  const Fixture& f = Encoded();
  int top = -1;
  for (const auto& q : f.stream.header.quantizers) top = std::max(top, q.top_bitplane);
  ASSERT_EQ(f.stream.packets.size(), static_cast<size_t>(top + 1));
  EXPECT_EQ(f.stream.header.packets.check.size(), 2 * f.stream.packets.size());
  EXPECT_EQ(f.stream.header.packets.distortion_step.size(), f.stream.packets.size());
  EXPECT_EQ(f.stream.header.packets.chain_distortion.size(), 1u);
  for (int i = 0; i <= top; ++i) {
    EXPECT_EQ(f.stream.header.packets.length[static_cast<size_t>(i)], f.stream.packets[i].size());
  }
}

TEST(ZerotreeCoderTest, AllPacketsReproduceTheMeshNearLosslessly) {
  const Fixture& f = Encoded();
  const auto decoded = DecodePrefix(f.stream, f.stream.packets.size());
  const double psnr = Psnr(f.mesh.positions, decoded, f.diag);
  std::printf("PGC BumpySphere(4): %zu packets, PSNR %.2f dB\n",
              f.stream.packets.size(), psnr);
  EXPECT_GE(psnr, 90.0);
  const double step = std::ldexp(f.diag, -16);
  for (size_t v = 0; v < decoded.size(); ++v) {
    EXPECT_LT((decoded[v] - f.mesh.positions[v]).norm(), 4 * step) << v;
  }
}

// A refinement bit moves a coefficient to the midpoint of a narrower cell,
// which can be farther from its value; summed over a whole bitplane the error
// falls, but the test allows a hair (0.01 dB) rather than pin that.
constexpr double kPsnrSlackDb = 0.01;

TEST(ZerotreeCoderTest, PsnrNeverDecreasesPacketByPacket) {
  const Fixture& f = Encoded();
  auto d = NewDecoder(f.stream);
  double previous = Psnr(f.mesh.positions, d->Positions(), f.diag);
  for (size_t i = 0; i < f.stream.packets.size(); ++i) {
    ASSERT_TRUE(d->AddPacket(f.stream.packets[i]).ok()) << i;
    const double psnr = Psnr(f.mesh.positions, d->Positions(), f.diag);
    EXPECT_GE(psnr, previous - kPsnrSlackDb) << "packet " << i;
    previous = psnr;
  }
}

TEST(ZerotreeCoderTest, EveryPrefixDecodesToTheIncrementalResult) {
  const Fixture& f = Encoded();
  auto d = NewDecoder(f.stream);
  for (size_t n = 0; n <= f.stream.packets.size(); ++n) {
    if (n > 0) {
      ASSERT_TRUE(d->AddPacket(f.stream.packets[n - 1]).ok());
    }
    EXPECT_EQ(DecodePrefix(f.stream, n), d->Positions()) << n << " packets";
  }
}

TEST(ZerotreeCoderTest, DistortionFiguresMatchTheDecodedError) {
  // The index's per-packet reductions, summed, predict the squared error of
  // every prefix up to the frame mismatch of a truncated decode.
  const Fixture& f = Encoded();
  auto d = NewDecoder(f.stream);
  const DistortionEstimates estimates =
      ReadDistortionIndex(f.stream.header, PgcPacketChains(f.stream.header));
  double estimate = estimates.start();
  for (size_t i = 0; i < f.stream.packets.size(); ++i) {
    ASSERT_TRUE(d->AddPacket(f.stream.packets[i]).ok());
    estimate -= estimates.reduction[i];
    const auto decoded = d->Positions();
    double sse = 0;
    for (size_t v = 0; v < decoded.size(); ++v) {
      sse += (decoded[v] - f.mesh.positions[v]).squaredNorm();
    }
    // Gains are measured on a regular torus, so only the order of magnitude
    // is pinned.
    if (sse > 1e-12) {
      EXPECT_LT(std::abs(std::log10(std::max(estimate, 1e-30) / sse)), 0.5) << i;
    }
  }
}

TEST(ZerotreeCoderTest, RoundTripsOpenMeshAndSingleLevel) {
  for (const auto& [base, levels] :
       std::vector<std::pair<TriMesh, int>>{{OpenPatch(), 3}, {Octahedron(), 1}}) {
    auto sr = Subdivide(base, levels, SubdivisionScheme::kButterfly);
    ASSERT_TRUE(sr.ok());
    std::mt19937 rng(7);
    std::normal_distribution<double> noise(0, 1e-2);
    for (Vec3& p : sr->positions) p += Vec3(noise(rng), noise(rng), noise(rng));
    auto s = EncodePgc(*sr, testing::EqualStepOptions());
    ASSERT_TRUE(s.ok()) << s.status().ToString();
    const auto& reference = s->mesh.positions;
    const double diag = BoundingBox(reference).Diagonal();
    EXPECT_GE(Psnr(reference, DecodePrefix(*s, s->packets.size()), diag), 90.0)
        << levels << " levels";
  }
}

TEST(ZerotreeCoderTest, SetMaximaCoverDescendantsAndGrandDescendants) {
  auto sr = Subdivide(OpenPatch(), 4, SubdivisionScheme::kMidpoint);
  ASSERT_TRUE(sr.ok());
  const SemiRegularHierarchy& h = *sr->hierarchy;
  std::mt19937 rng(3);
  std::vector<std::vector<uint32_t>> q0(h.levels());
  for (int j = 0; j < h.levels(); ++j) {
    q0[j].resize(h.subband_size(j));
    for (auto& q : q0[j]) q = rng() % 1000;
  }
  const ZerotreeSetMaxima m = ComputeZerotreeSetMaxima(h, q0);
  // Brute force: walk the tree of each coefficient of d^0 and d^1.
  std::array<uint32_t, 4> children;
  for (int j = 0; j < 2; ++j) {
    for (uint32_t k = 0; k < h.subband_size(j); ++k) {
      uint32_t d = 0, l = 0;
      std::vector<uint32_t> level{k};
      for (int i = j + 1; i < h.levels(); ++i) {
        std::vector<uint32_t> next;
        for (uint32_t e : level) {
          const int n = h.Children(i - 1, e, children);
          next.insert(next.end(), children.begin(), children.begin() + n);
        }
        for (uint32_t e : next) {
          d = std::max(d, q0[i][e]);
          if (i >= j + 2) l = std::max(l, q0[i][e]);
        }
        level = std::move(next);
      }
      EXPECT_EQ(m.d[j][k], d) << j << " " << k;
      EXPECT_EQ(m.l[j][k], l) << j << " " << k;
    }
  }
}

TEST(ZerotreeCoderTest, DecoderRejectsCorruptAndSurplusPackets) {
  const Fixture& f = Encoded();
  auto d = NewDecoder(f.stream);
  std::string bad = f.stream.packets[0];
  ASSERT_FALSE(bad.empty());
  bad[0] = static_cast<char>(bad[0] ^ 0x40);
  EXPECT_EQ(d->AddPacket(bad).code(), StatusCode::kParseError);
  EXPECT_EQ(d->AddPacket(f.stream.packets[0] + "x").code(), StatusCode::kParseError);
  // Nothing changed: the right packet still decodes.
  EXPECT_TRUE(d->AddPacket(f.stream.packets[0]).ok());
  for (size_t i = 1; i < f.stream.packets.size(); ++i) {
    ASSERT_TRUE(d->AddPacket(f.stream.packets[i]).ok());
  }
  EXPECT_EQ(d->AddPacket("").code(), StatusCode::kInvalidArgument);
}

TEST(ZerotreeCoderTest, HeaderIsRefusedByTheMwvDecoderAndViceVersa) {
  const Fixture& f = Encoded();
  EXPECT_FALSE(ProgressiveDecoder::Create(f.stream.header).ok());
  auto sim = EncodeMesh(f.mesh, EncodeOptions{});
  ASSERT_TRUE(sim.ok());
  EXPECT_FALSE(PgcDecoder::Create(sim->header).ok());
  StreamHeader wrong = f.stream.header;
  wrong.packets.distortion_step.push_back('\0');
  EXPECT_EQ(PgcDecoder::Create(wrong).status().code(), StatusCode::kParseError);
}

}  // namespace
}  // namespace meshwave
