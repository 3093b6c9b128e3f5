#include "meshwave/progressive_decoder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <random>
#include <thread>
#include <vector>

#include "codec/stream/stream_test_util.h"
#include "meshwave/container.h"
#include "meshwave/mesh_stats.h"
#include "meshwave/progression.h"
#include "stream/packet_index.h"

namespace meshwave {
namespace {

using testing::BumpySphere;
using testing::Psnr;

struct Fixture {
  SemiRegularMesh mesh;
  EncodedStream stream;
  double diag = 0;
};

const Fixture& Encoded(CoderKind coder) {
  static std::map<CoderKind, Fixture> cache;
  auto it = cache.find(coder);
  if (it != cache.end()) return it->second;
  Fixture f;
  f.mesh = BumpySphere(4);
  EncodeOptions options = testing::EqualStepOptions();
  options.coder = coder;
  auto s = EncodeMesh(f.mesh, options);
  EXPECT_TRUE(s.ok()) << s.status().ToString();
  f.stream = *std::move(s);
  f.mesh = f.stream.mesh;  // the stream's vertex order
  f.diag = BoundingBox(f.mesh.positions).Diagonal();
  return cache.emplace(coder, std::move(f)).first->second;
}

std::unique_ptr<ProgressiveDecoder> NewDecoder(const EncodedStream& s) {
  auto d = ProgressiveDecoder::Create(s.header);
  EXPECT_TRUE(d.ok()) << d.status().ToString();
  return std::move(d).value();
}

class CoderTest : public ::testing::TestWithParam<CoderKind> {};

TEST_P(CoderTest, AllPacketsReproduceTheMeshNearLosslessly) {
  const Fixture& f = Encoded(GetParam());
  auto d = NewDecoder(f.stream);
  for (uint32_t id = 0; id < f.stream.packets.size(); ++id) {
    ASSERT_TRUE(d->AddPacket(id, f.stream.packets[id]).ok()) << id;
  }
  const auto decoded = d->Positions();
  const double psnr = Psnr(f.mesh.positions, decoded, f.diag);
  EXPECT_GE(psnr, 90.0);
  // Within a few finest steps of every vertex (step = diag * 2^-16).
  const double step = std::ldexp(f.diag, -16);
  for (size_t v = 0; v < decoded.size(); ++v) {
    EXPECT_LT((decoded[v] - f.mesh.positions[v]).norm(), 4 * step) << v;
  }
}

TEST_P(CoderTest, SetUpOnOneOrTwoThreadsDecodesTheSame) {
  const Fixture& f = Encoded(GetParam());
  std::vector<std::vector<Vec3>> results;
  for (int threads : {1, 2}) {
    DecoderOptions options;
    options.threads = threads;
    auto d = ProgressiveDecoder::Create(f.stream.header, options);
    ASSERT_TRUE(d.ok()) << d.status().ToString();
    // Half the packets: a partial state exercises the octrees as well.
    for (uint32_t id = 0; id < f.stream.packets.size() / 2; ++id) {
      ASSERT_TRUE((*d)->AddPacket(id, f.stream.packets[id]).ok()) << id;
    }
    results.push_back((*d)->Positions());
  }
  ASSERT_EQ(results[0].size(), results[1].size());
  for (size_t v = 0; v < results[0].size(); ++v) ASSERT_EQ(results[0][v], results[1][v]) << v;
  EXPECT_NE(results[0], std::vector<Vec3>(results[0].size(), results[0][0]));
}

TEST_P(CoderTest, ADeferredSetUpAnswersAsACompletedOne) {
  const Fixture& f = Encoded(GetParam());
  const int levels = static_cast<int>(f.stream.header.transform.levels);
  for (int threads : {1, 2}) {
    DecoderOptions options;
    options.threads = threads;
    // `lazy` answers before its set-up is built (threads 1: nothing is built
    // until needed), `ready` after CompleteSetUp.
    auto lazy = ProgressiveDecoder::Create(f.stream.header, options);
    auto ready = ProgressiveDecoder::Create(f.stream.header, options);
    ASSERT_TRUE(lazy.ok() && ready.ok());
    (*ready)->CompleteSetUp();
    EXPECT_EQ((*lazy)->DetailLevels(), (*ready)->DetailLevels());
    EXPECT_EQ((*lazy)->CompleteLevels(), (*ready)->CompleteLevels());
    for (int level = 0; level <= levels; ++level) {
      EXPECT_EQ((*lazy)->Positions(level), (*ready)->Positions(level)) << level;
    }
    // Then packets, a Reset and packets again: the same as a fresh decoder.
    auto fresh = ProgressiveDecoder::Create(f.stream.header, options);
    ASSERT_TRUE(fresh.ok());
    for (uint32_t id = 0; id < f.stream.packets.size(); ++id) {
      ASSERT_TRUE((*lazy)->AddPacket(id, f.stream.packets[id]).ok()) << id;
    }
    (*lazy)->Reset();
    EXPECT_EQ((*lazy)->DetailLevels(), 0);
    EXPECT_EQ((*lazy)->Positions(), (*ready)->Positions());
    for (uint32_t id = 0; id < f.stream.packets.size() / 2; ++id) {
      ASSERT_TRUE((*lazy)->AddPacket(id, f.stream.packets[id]).ok()) << id;
      ASSERT_TRUE((*fresh)->AddPacket(id, f.stream.packets[id]).ok()) << id;
    }
    EXPECT_EQ((*lazy)->Positions(), (*fresh)->Positions());
    EXPECT_EQ((*lazy)->DetailLevels(), (*fresh)->DetailLevels());
    EXPECT_EQ((*lazy)->CompleteLevels(), (*fresh)->CompleteLevels());
  }
}

TEST_P(CoderTest, MeshesAskedOutOfOrderAndFromTwoThreadsAreTheCompletedOnes) {
  const Fixture& f = Encoded(GetParam());
  const int levels = static_cast<int>(f.stream.header.transform.levels);
  DecoderOptions options;
  options.threads = 1;
  auto ready = ProgressiveDecoder::Create(f.stream.header, options);
  ASSERT_TRUE(ready.ok());
  (*ready)->CompleteSetUp();
  const size_t half = f.stream.packets.size() / 2;
  for (uint32_t id = 0; id < half; ++id) {
    ASSERT_TRUE((*ready)->AddPacket(id, f.stream.packets[id]).ok()) << id;
  }
  std::vector<std::vector<Vec3>> expected;
  for (int level = 0; level <= levels; ++level) expected.push_back((*ready)->Positions(level));
  for (int threads : {1, 2}) {
    options.threads = threads;
    auto d = ProgressiveDecoder::Create(f.stream.header, options);
    ASSERT_TRUE(d.ok());
    for (uint32_t id = 0; id < half; ++id) {
      ASSERT_TRUE((*d)->AddPacket(id, f.stream.packets[id]).ok()) << id;
    }
    // Finest first on one thread, coarsest first on another.
    std::vector<std::vector<Vec3>> down(levels + 1), up(levels + 1);
    std::thread other([&] {
      for (int level = levels; level >= 0; --level) down[level] = (*d)->Positions(level);
    });
    for (int level = 0; level <= levels; ++level) up[level] = (*d)->Positions(level);
    other.join();
    for (int level = 0; level <= levels; ++level) {
      EXPECT_EQ(down[level], expected[level]) << threads << " threads, level " << level;
      EXPECT_EQ(up[level], expected[level]) << threads << " threads, level " << level;
    }
  }
}

TEST_P(CoderTest, ADecoderDestroyedDuringItsSetUpIsFine) {
  const Fixture& f = Encoded(GetParam());
  DecoderOptions options;
  options.threads = 2;
  for (int i = 0; i < 3; ++i) {
    auto d = ProgressiveDecoder::Create(f.stream.header, options);
    ASSERT_TRUE(d.ok());
    EXPECT_EQ((*d)->Positions(0).size(), f.stream.header.base.vertex_count);
  }  // each destroyed with its set-up threads possibly still running
}

TEST_P(CoderTest, FinalMeshIsIdenticalInEveryOrder) {
  const Fixture& f = Encoded(GetParam());
  std::vector<std::vector<Vec3>> results;
  for (Progression p : {Progression::kQuality, Progression::kResolution, Progression::kRd}) {
    auto d = NewDecoder(f.stream);
    const auto order = PacketOrder(f.stream.header, p);
    ASSERT_EQ(order.size(), f.stream.packets.size());
    for (uint32_t id : order) {
      ASSERT_TRUE(d->AddPacket(id, f.stream.packets[id]).ok())
          << ProgressionName(p) << " packet " << id;
    }
    results.push_back(d->Positions());
  }
  EXPECT_EQ(results[0], results[1]);
  EXPECT_EQ(results[0], results[2]);
}

TEST_P(CoderTest, PsnrNeverDecreasesInQualityAndRdOrder) {
  const Fixture& f = Encoded(GetParam());
  for (Progression p : {Progression::kQuality, Progression::kRd}) {
    auto d = NewDecoder(f.stream);
    double last = Psnr(f.mesh.positions, d->Positions(), f.diag);
    for (uint32_t id : PacketOrder(f.stream.header, p)) {
      ASSERT_TRUE(d->AddPacket(id, f.stream.packets[id]).ok());
      const double now = Psnr(f.mesh.positions, d->Positions(), f.diag);
      EXPECT_GE(now, last - 1e-9) << ProgressionName(p) << " packet " << id;
      last = now;
    }
  }
}

TEST_P(CoderTest, ResolutionOrderWithMaxLevelGivesThatLevelsMesh) {
  const Fixture& f = Encoded(GetParam());
  for (int level = 0; level <= 4; ++level) {
    auto d = NewDecoder(f.stream);
    const PacketLayout layout(f.stream.header);
    for (uint32_t id : PacketOrder(f.stream.header, Progression::kResolution, level)) {
      ASSERT_LT(layout.Subband(id), level);
      ASSERT_TRUE(d->AddPacket(id, f.stream.packets[id]).ok());
    }
    const TriMesh m = d->Mesh(level);
    EXPECT_EQ(m.positions.size(), f.mesh.hierarchy->vertex_count(level));
    EXPECT_EQ(m.faces.size(), f.mesh.hierarchy->faces(level).size());
    EXPECT_EQ(d->CompleteLevels(), level);
  }
}

// DetailLevels: the base alone has none, the whole stream all J; it rises
// only with a packet of the level it rises to; every finer level's details
// are zero (the coarse vertices of the finest mesh are the detail level's,
// bit for bit); a resolution-ordered prefix to a level reaches that level.
TEST_P(CoderTest, DetailLevelsIsTheFinestLevelWithANonzeroDetail) {
  const Fixture& f = Encoded(GetParam());
  const int levels = f.mesh.hierarchy->levels();
  const PacketLayout layout(f.stream.header);
  auto d = NewDecoder(f.stream);
  EXPECT_EQ(d->DetailLevels(), 0);
  int last = 0;
  for (uint32_t id : PacketOrder(f.stream.header, Progression::kQuality)) {
    ASSERT_TRUE(d->AddPacket(id, f.stream.packets[id]).ok());
    const int now = d->DetailLevels();
    ASSERT_GE(now, last) << "packet " << id;
    if (now > last) {
      EXPECT_EQ(layout.Subband(id), now - 1) << "packet " << id;
    }
    if (now < levels) {
      const std::vector<Vec3> finest = d->Positions();
      const std::vector<Vec3> coarse = d->Positions(now);
      ASSERT_EQ(coarse.size(), f.mesh.hierarchy->vertex_count(now));
      EXPECT_TRUE(std::equal(coarse.begin(), coarse.end(), finest.begin())) << "packet " << id;
    }
    last = now;
  }
  EXPECT_EQ(last, levels);
  for (int level = 1; level <= levels; ++level) {
    auto r = NewDecoder(f.stream);
    for (uint32_t id : PacketOrder(f.stream.header, Progression::kResolution, level)) {
      ASSERT_TRUE(r->AddPacket(id, f.stream.packets[id]).ok());
    }
    EXPECT_EQ(r->DetailLevels(), level);
  }
}

TEST_P(CoderTest, RandomDependencyRespectingOrdersGiveTheSameMesh) {
  const Fixture& f = Encoded(GetParam());
  auto reference = NewDecoder(f.stream);
  for (uint32_t id = 0; id < f.stream.packets.size(); ++id) {
    ASSERT_TRUE(reference->AddPacket(id, f.stream.packets[id]).ok());
  }
  std::mt19937 rng(5);
  for (int trial = 0; trial < 5; ++trial) {
    auto d = NewDecoder(f.stream);
    std::vector<uint32_t> pending(f.stream.packets.size());
    std::iota(pending.begin(), pending.end(), 0u);
    while (!pending.empty()) {
      std::vector<size_t> ready;
      for (size_t i = 0; i < pending.size(); ++i) {
        if (d->DependenciesMet(pending[i])) ready.push_back(i);
      }
      ASSERT_FALSE(ready.empty());
      const size_t pick = ready[rng() % ready.size()];
      ASSERT_TRUE(d->AddPacket(pending[pick], f.stream.packets[pending[pick]]).ok());
      pending.erase(pending.begin() + static_cast<long>(pick));
    }
    EXPECT_EQ(d->Positions(), reference->Positions());
  }
}

INSTANTIATE_TEST_SUITE_P(Coders, CoderTest,
                         ::testing::Values(CoderKind::k3xC, CoderKind::kSim),
                         [](const auto& i) { return std::string(CoderKindName(i.param)); });

TEST(ProgressiveDecoderTest, RefusesPacketBeforeItsDependencies) {
  const Fixture& f = Encoded(CoderKind::k3xC);
  auto d = NewDecoder(f.stream);
  // The second packet of subband 0 needs the first.
  Status s = d->AddPacket(1, f.stream.packets[1]);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("needs packet 0"), std::string::npos) << s.message();
  // The decoder stays usable.
  EXPECT_TRUE(d->AddPacket(0, f.stream.packets[0]).ok());
  EXPECT_TRUE(d->AddPacket(1, f.stream.packets[1]).ok());
  EXPECT_EQ(d->AddPacket(1, f.stream.packets[1]).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(d->AddPacket(99999, "").code(), StatusCode::kInvalidArgument);
}

TEST(ProgressiveDecoderTest, PacketLayoutDerivesSubbandAndBitplaneFromTheQuantizers) {
  const auto& f = Encoded(CoderKind::k3xC);
  const PacketLayout layout(f.stream.header);
  ASSERT_EQ(layout.count(), static_cast<int>(f.stream.packets.size()));
  int id = 0;
  for (int j = 0; j < layout.levels(); ++j) {
    int top = -1;
    for (int c = 0; c < 3; ++c) {
      top = std::max(top, f.stream.header.quantizers[static_cast<size_t>(3 * j + c)].top_bitplane);
    }
    for (int b = top; b >= 0; --b, ++id) {
      EXPECT_EQ(layout.Subband(static_cast<uint32_t>(id)), j);
      EXPECT_EQ(layout.Bitplane(static_cast<uint32_t>(id)), b);
      EXPECT_EQ(layout.Id(j, b), id);
    }
  }
  EXPECT_EQ(id, layout.count());
  EXPECT_EQ(layout.Id(0, layout.Top(0) + 1), -1);
}

TEST(ProgressiveDecoderTest, ThreeXcNeedsTheParentSubbandsBitplane) {
  const Fixture& f = Encoded(CoderKind::k3xC);
  auto d = NewDecoder(f.stream);
  const PacketLayout layout(f.stream.header);
  // First packet of subband 1 (its top bitplane) needs subband 0 at that
  // bitplane when subband 0 has one.
  uint32_t first1 = 0;
  while (layout.Subband(first1) != 1) ++first1;
  EXPECT_FALSE(d->DependenciesMet(first1));
  EXPECT_EQ(d->AddPacket(first1, f.stream.packets[first1]).code(),
            StatusCode::kInvalidArgument);
}

TEST(ProgressiveDecoderTest, RefusesCorruptPayload) {
  const Fixture& f = Encoded(CoderKind::k3xC);
  auto d = NewDecoder(f.stream);
  std::string bad = f.stream.packets[0];
  ASSERT_FALSE(bad.empty());
  bad[bad.size() / 2] ^= 0x10;
  Status s = d->AddPacket(0, bad);
  EXPECT_EQ(s.code(), StatusCode::kParseError);
  EXPECT_NE(s.message().find("CRC-16"), std::string::npos);
  EXPECT_EQ(d->AddPacket(0, f.stream.packets[0].substr(1)).code(), StatusCode::kParseError);
  EXPECT_TRUE(d->AddPacket(0, f.stream.packets[0]).ok());
}

TEST(ProgressiveDecoderTest, ResetForgetsEveryPacket) {
  const Fixture& f = Encoded(CoderKind::k3xC);
  const uint32_t n = static_cast<uint32_t>(f.stream.packets.size());
  auto fresh = NewDecoder(f.stream);
  auto d = NewDecoder(f.stream);
  for (uint32_t id = 0; id < n / 2; ++id) ASSERT_TRUE(d->AddPacket(id, f.stream.packets[id]).ok());
  ASSERT_NE(d->Positions(), fresh->Positions());
  d->Reset();
  EXPECT_EQ(d->packets_decoded(), 0u);
  EXPECT_EQ(d->payload_bytes_decoded(), 0u);
  EXPECT_FALSE(d->HasPacket(0));
  EXPECT_EQ(d->CompleteLevels(), 0);
  EXPECT_EQ(d->DetailLevels(), 0);
  EXPECT_EQ(d->EstimatedPsnr(), fresh->EstimatedPsnr());
  EXPECT_EQ(d->Positions(), fresh->Positions());  // the base mesh only
  for (uint32_t id = 0; id < n; ++id) {
    ASSERT_TRUE(d->AddPacket(id, f.stream.packets[id]).ok()) << id;
    ASSERT_TRUE(fresh->AddPacket(id, f.stream.packets[id]).ok()) << id;
  }
  EXPECT_EQ(d->Positions(), fresh->Positions());  // bit for bit
  EXPECT_EQ(d->EstimatedPsnr(), fresh->EstimatedPsnr());
}

// A payload that passes its check but ends before its symbols (what a
// malicious server can send) breaks the decoder; Reset makes it usable.
TEST(ProgressiveDecoderTest, ResetRecoversFromAPayloadThatDoesNotDecode) {
  const Fixture& f = Encoded(CoderKind::k3xC);
  const uint32_t last = static_cast<uint32_t>(f.stream.packets.size()) - 1;
  ASSERT_GT(f.stream.packets[last].size(), 8u);
  StreamHeader h = f.stream.header;
  const std::string cut = f.stream.packets[last].substr(0, 1);
  h.packets.length[last] = 1;
  const uint16_t check = PacketCheck(cut);
  h.packets.check[2 * last] = static_cast<char>(check >> 8);
  h.packets.check[2 * last + 1] = static_cast<char>(check & 0xff);
  auto created = ProgressiveDecoder::Create(h);
  ASSERT_TRUE(created.ok()) << created.status().ToString();
  ProgressiveDecoder& d = **created;
  auto reference = NewDecoder(f.stream);
  for (uint32_t id = 0; id < last; ++id) {
    ASSERT_TRUE(d.AddPacket(id, f.stream.packets[id]).ok()) << id;
    ASSERT_TRUE(reference->AddPacket(id, f.stream.packets[id]).ok()) << id;
  }
  EXPECT_EQ(d.AddPacket(last, cut).code(), StatusCode::kParseError);
  EXPECT_NE(d.AddPacket(last, cut).message().find("unusable"), std::string::npos);
  d.Reset();
  for (uint32_t id = 0; id < last; ++id) ASSERT_TRUE(d.AddPacket(id, f.stream.packets[id]).ok());
  EXPECT_EQ(d.Positions(), reference->Positions());
}

TEST(ProgressiveDecoderTest, RefusesAHeaderOverItsFaceLimitBeforeBuildingIt) {
  const Fixture& f = Encoded(CoderKind::k3xC);
  DecoderOptions options;
  options.max_faces = f.stream.header.faces;
  EXPECT_TRUE(ProgressiveDecoder::Create(f.stream.header, options).ok());
  options.max_faces = f.stream.header.faces - 1;
  auto refused = ProgressiveDecoder::Create(f.stream.header, options);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.status().code(), StatusCode::kUnsupported);
  EXPECT_NE(refused.status().message().find("limit"), std::string::npos);
}

TEST(ProgressiveDecoderTest, EstimatedPsnrTracksTheTruth) {
  const Fixture& f = Encoded(CoderKind::k3xC);
  auto d = NewDecoder(f.stream);
  for (uint32_t id : PacketOrder(f.stream.header, Progression::kQuality)) {
    ASSERT_TRUE(d->AddPacket(id, f.stream.packets[id]).ok());
    const double truth = Psnr(f.mesh.positions, d->Positions(), f.diag);
    if (truth < 80) {
      EXPECT_NEAR(d->EstimatedPsnr(), truth, 3.0) << id;
    }
  }
}

}  // namespace
}  // namespace meshwave
