// The original layer in the stream (format version 10): the user's faces
// over its own vertex ids and its positions within the precision's bound
// from a complete decode; the layer last in every order, the packets before
// it unchanged; each positions packet closer than the one before; refusals
// of layers a version cannot hold or that do not fit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <random>

#include "codec/stream/stream_test_util.h"
#include "meshwave/container.h"
#include "meshwave/encoder.h"
#include "meshwave/mesh_io.h"
#include "meshwave/progression.h"
#include "meshwave/progressive_decoder.h"
#include "meshwave/region.h"
#include "meshwave/region_order.h"
#include "stream/packet_index.h"
#include "stream/stream_format.h"
#include "test_data.h"

namespace meshwave {
namespace {

// A face as a key that keeps its cyclic order: rotated to its smallest id.
Face Rotated(Face f) {
  std::rotate(f.begin(), std::min_element(f.begin(), f.end()), f.end());
  return f;
}

std::map<Face, int> FaceSet(const std::vector<Face>& faces) {
  std::map<Face, int> set;
  for (const Face& f : faces) ++set[Rotated(f)];
  return set;
}

// A mesh unlike the remesh in every way the layer must keep: a coarser
// level of it, vertices shuffled, a vertex in no face, a repeated face, a
// face against the others' orientation.
TriMesh AwkwardOriginal(const SemiRegularMesh& sr) {
  TriMesh level = sr.Level(2);
  const size_t n = level.positions.size();
  std::vector<uint32_t> new_of_old(n);
  std::iota(new_of_old.begin(), new_of_old.end(), 0u);
  std::shuffle(new_of_old.begin(), new_of_old.end(), std::mt19937(7));
  TriMesh out;
  out.positions.resize(n + 1);
  for (size_t v = 0; v < n; ++v)
    out.positions[new_of_old[v]] = level.positions[v];
  out.positions[n] = Vec3(0.1, 0.2, 0.3);  // in no face
  for (const Face& f : level.faces) {
    out.faces.push_back({new_of_old[f[0]], new_of_old[f[1]], new_of_old[f[2]]});
  }
  out.faces.push_back(out.faces[5]);
  const Face f = out.faces[9];
  out.faces.push_back({f[0], f[2], f[1]});
  return out;
}

struct Streams {
  SemiRegularMesh remesh;
  TriMesh original;
  EncodedStream plain;  // without the layer
  EncodedStream layered;
};

const Streams& TestStreams() {
  static const Streams* streams = [] {
    auto* s = new Streams;
    s->remesh = testing::BumpySphere(3);
    s->original = AwkwardOriginal(s->remesh);
    auto plain = EncodeMesh(s->remesh, EncodeOptions{});
    EXPECT_TRUE(plain.ok()) << plain.status().ToString();
    s->plain = std::move(plain).value();
    VertexAttributes attributes;
    attributes.original = &s->original;
    auto layered = EncodeMesh(s->remesh, EncodeOptions{}, attributes);
    EXPECT_TRUE(layered.ok()) << layered.status().ToString();
    s->layered = std::move(layered).value();
    return s;
  }();
  return *streams;
}

TEST(OriginalLayerStreamTest, CompleteDecodeIsTheOriginalWithinThePrecision) {
  const Streams& s = TestStreams();
  const StreamHeader& h = s.layered.header;
  ASSERT_TRUE(h.original.has_value());
  EXPECT_EQ(h.format_version, kStreamFormatVersion);
  auto d = testing::DecoderOf(s.layered);
  ASSERT_TRUE(d->HasOriginal());
  for (uint32_t id : PacketOrder(h, Progression::kRd)) {
    ASSERT_TRUE(d->AddPacket(id, s.layered.packets[id]).ok()) << id;
  }
  ASSERT_TRUE(d->OriginalReady());
  const TriMesh mesh = d->OriginalMesh();
  ASSERT_EQ(mesh.positions.size(), s.original.positions.size());
  EXPECT_EQ(FaceSet(mesh.faces), FaceSet(s.original.faces));
  // Vertex i is the original's vertex i: within half a step per coordinate.
  const double bound = h.original->step / 2 * (1 + 1e-9);
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    const Vec3 e = (mesh.positions[v] - s.original.positions[v]).cwiseAbs();
    ASSERT_LE(e.maxCoeff(), bound) << "vertex " << v;
  }
}

// The layer on a real mesh: a complete decode gives back its own faces
// over its own vertex ids and every coordinate within half the finest step
// the precision names (diagonal x 2^-16). The remesh before the layer is a
// stand-in (the layer depends on it only for its number of refinement
// planes, from the remesh's PSNR): a remesh of each shared mesh would cost
// minutes, and the CLI test runs the whole pipeline on a sample.
void ExpectLayerGivesBack(const std::filesystem::path& file) {
  SCOPED_TRACE(file.filename().string());
  Result<TriMesh> original = ReadMesh(file);
  ASSERT_TRUE(original.ok()) << original.status().ToString();
  VertexAttributes attributes;
  attributes.original = &*original;
  attributes.original_remesh_psnr_db = 75;  // a default remesh's order
  const EncodeOptions options;
  auto stream = EncodeMesh(testing::BumpySphere(2), options, attributes);
  ASSERT_TRUE(stream.ok()) << stream.status().ToString();
  const StreamHeader& h = stream->header;
  ASSERT_TRUE(h.original.has_value());
  auto d = testing::DecoderOf(*stream);
  for (uint32_t id : PacketOrder(h, Progression::kQuality)) {
    ASSERT_TRUE(d->AddPacket(id, stream->packets[id]).ok()) << id;
  }
  ASSERT_TRUE(d->OriginalReady());
  const TriMesh mesh = d->OriginalMesh();
  ASSERT_EQ(mesh.positions.size(), original->positions.size());
  EXPECT_EQ(FaceSet(mesh.faces), FaceSet(original->faces));
  Vec3 low = original->positions[0], high = low;
  for (const Vec3& p : original->positions) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  const double diagonal = (high - low).norm();
  EXPECT_LE(h.original->step,
            diagonal * std::ldexp(1.0, -options.precision) * (1 + 1e-9));
  double worst = 0;
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    worst = std::max(
        worst,
        (mesh.positions[v] - original->positions[v]).cwiseAbs().maxCoeff());
  }
  EXPECT_LE(worst, h.original->step / 2 * (1 + 1e-9))
      << original->positions.size() << " vertices";
}

// The shipped samples, the textured and coloured ones' geometry included
// (their streams carry the attributes on the remesh and leave the layer out
// by default).
TEST(OriginalLayerStreamTest, EverySampleComesBackWhole) {
  for (const char* name : {"elephant.off", "holes.off", "textured/die.obj",
                           "textured/hue_ball.ply"}) {
    ExpectLayerGivesBack(testing::SampleMesh(name));
  }
}

TEST(OriginalLayerStreamTest, EverySharedMeshComesBackWhole) {
  MESHWAVE_REQUIRE_SHARED_MESH();
  for (const std::filesystem::path& file : testing::AllSharedMeshes())
    ExpectLayerGivesBack(file);
}

TEST(OriginalLayerStreamTest, LastInEveryOrderAndNothingBeforeItMoves) {
  const Streams& s = TestStreams();
  const StreamHeader& h = s.layered.header;
  const PacketLayout layout(h);
  const int parts = layout.original_parts();
  ASSERT_EQ(parts, 2 + static_cast<int>(h.original->refinement_planes));
  const size_t first = s.plain.packets.size();
  ASSERT_EQ(s.layered.packets.size(), first + static_cast<size_t>(parts));
  // The remesh's packets are the same bytes.
  for (size_t id = 0; id < first; ++id)
    ASSERT_EQ(s.layered.packets[id], s.plain.packets[id]) << id;
  for (Progression p :
       {Progression::kQuality, Progression::kResolution, Progression::kRd}) {
    SCOPED_TRACE(ProgressionName(p));
    const std::vector<uint32_t> order = PacketOrder(h, p);
    const std::vector<uint32_t> before(order.begin(), order.end() - parts);
    EXPECT_EQ(before, PacketOrder(s.plain.header, p));
    for (int part = 0; part < parts; ++part) {
      EXPECT_EQ(order[before.size() + static_cast<size_t>(part)],
                first + static_cast<size_t>(part));
    }
    // A coarser mesh leaves the layer out.
    const std::vector<uint32_t> coarse = PacketOrder(h, p, layout.levels() - 1);
    EXPECT_TRUE(std::none_of(coarse.begin(), coarse.end(), [&](uint32_t id) {
      return layout.IsOriginal(id);
    }));
  }
  // The region order: once each, last.
  auto precincts = StreamPrecincts::Create(h);
  ASSERT_TRUE(precincts.ok()) << precincts.status().ToString();
  auto d = testing::DecoderOf(s.layered);
  std::vector<std::vector<uint32_t>> lengths(s.layered.packets.size());
  for (uint32_t id = 0; id < s.layered.packets.size(); ++id) {
    auto l = PartLengths(d->held(), id, s.layered.packets[id]);
    ASSERT_TRUE(l.ok());
    lengths[id] = *l;
  }
  Region region;
  region.shape = SphereRegion{Vec3(1, 0, 0), 0.5};
  const auto units = RegionOrder(h, *precincts, lengths, region, d->held());
  ASSERT_GE(units.size(), static_cast<size_t>(parts));
  for (int part = 0; part < parts; ++part) {
    const StreamUnit& u =
        units[units.size() - static_cast<size_t>(parts - part)];
    EXPECT_EQ(u.id, first + static_cast<size_t>(part));
    EXPECT_TRUE(u.whole());
  }
}

TEST(OriginalLayerStreamTest, EachPositionsPacketBringsTheMeshCloser) {
  const Streams& s = TestStreams();
  const StreamHeader& h = s.layered.header;
  const PacketLayout layout(h);
  auto d = testing::DecoderOf(s.layered);
  for (uint32_t id = 0; id < s.plain.packets.size(); ++id) {
    ASSERT_TRUE(d->AddPacket(id, s.layered.packets[id]).ok());
  }
  EXPECT_FALSE(d->OriginalReady());
  EXPECT_TRUE(d->OriginalMesh().positions.empty());
  // Positions before the connectivity: refused, nothing changed.
  const auto coarse = static_cast<uint32_t>(layout.OriginalId(1));
  EXPECT_EQ(d->AddPacket(coarse, s.layered.packets[coarse]).code(),
            StatusCode::kInvalidArgument);
  ASSERT_TRUE(d->AddPacket(coarse - 1, s.layered.packets[coarse - 1]).ok());
  EXPECT_FALSE(d->OriginalReady());
  double previous = std::numeric_limits<double>::infinity();
  for (int part = 1; part < layout.original_parts(); ++part) {
    const auto id = static_cast<uint32_t>(layout.OriginalId(part));
    ASSERT_TRUE(d->AddPacket(id, s.layered.packets[id]).ok()) << part;
    ASSERT_TRUE(d->OriginalReady());
    const TriMesh mesh = d->OriginalMesh();
    double squared = 0;
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
      squared += (mesh.positions[v] - s.original.positions[v]).squaredNorm();
    }
    EXPECT_LT(squared, previous) << "positions packet " << part - 1;
    previous = squared;
  }
}

TEST(OriginalLayerStreamTest, RefusesALayerItsVersionOrItsFieldsCannotHold) {
  const Streams& s = TestStreams();
  StreamHeader h = s.layered.header;
  h.format_version = 9;
  EXPECT_NE(ValidateStreamHeader(h).message().find("original layer"),
            std::string::npos);
  // A version-9 stream without the layer still reads.
  StreamHeader v9 = s.plain.header;
  v9.format_version = 9;
  EXPECT_TRUE(ValidateStreamHeader(v9).ok());
  auto refused = [&](auto change, const std::string& words) {
    StreamHeader bad = s.layered.header;
    change(*bad.original);
    const Status status = ValidateStreamHeader(bad);
    EXPECT_EQ(status.code(), StatusCode::kParseError) << words;
    EXPECT_NE(status.message().find(words), std::string::npos)
        << status.message();
  };
  refused([](StreamHeader::Original& o) { o.vertex_count = 0; }, "0 vertices");
  refused([](StreamHeader::Original& o) { o.step = -1; },
          "finite positive step");
  refused([](StreamHeader::Original& o) { o.origin.pop_back(); },
          "3 finite origin");
  refused([](StreamHeader::Original& o) { o.refinement_planes = 9; },
          "refinement planes");
  refused([](StreamHeader::Original& o) { o.extent = 1u << 31; },
          "grid extent");
  // More faces than a decoder accepts: refused before anything is built.
  DecoderOptions small;
  small.max_faces = s.layered.header.faces;
  ASSERT_GT(s.layered.header.original->face_count, 0u);
  StreamHeader many = s.layered.header;
  many.original->face_count = s.layered.header.faces + 1;
  EXPECT_EQ(ProgressiveDecoder::Create(many, small).status().code(),
            StatusCode::kUnsupported);
  StreamHeader crowded = s.layered.header;
  crowded.original->vertex_count =
      static_cast<uint32_t>(s.layered.header.faces + 1);
  EXPECT_EQ(ProgressiveDecoder::Create(crowded, small).status().code(),
            StatusCode::kUnsupported);
  EXPECT_TRUE(ProgressiveDecoder::Create(s.layered.header, small).ok());
}

}  // namespace
}  // namespace meshwave
