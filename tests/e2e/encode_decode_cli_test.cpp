// End-to-end: `meshwave encode` and `meshwave decode` as a user runs them.
#include <gtest/gtest.h>

#include <google/protobuf/util/json_util.h>

#include <algorithm>
#include <fstream>

#include "codec/texture/png_testonly.h"
#include "e2e/cli_runner.h"
#include "meshwave/container.h"
#include "meshwave/encoder.h"
#include "meshwave/progression.h"
#include "meshwave/progressive_decoder.h"
#include "meshwave/subdivision.h"
#include "meshwave.pb.h"
#include "meshwave/mesh_io.h"
#include "meshwave/metrics.h"
#include "meshwave/mesh.h"
#include "meshwave/semiregular.h"

namespace meshwave {
namespace {

using testing::RunCli;
using testing::TempDir;

// Symmetric surface PSNR of `decoded` against `reference`, as `meshwave
// compare` gives it (peak = the reference's bounding-box diagonal): what a
// user judges a stream by. (The default quantises tangential detail 8 times
// coarser than normal detail: vertices slide along the surface, which a
// vertex-to-vertex PSNR would count and the surface distance does not.)
double PsnrAgainst(const std::filesystem::path& reference,
                   const std::filesystem::path& decoded) {
  auto a = ReadMesh(reference);
  auto b = ReadMesh(decoded);
  EXPECT_TRUE(a.ok() && b.ok());
  auto d = SymmetricSurfaceDistance(*a, *b);
  EXPECT_TRUE(d.ok()) << d.status().ToString();
  return d->PsnrDb(d->rms);
}

TEST(EncodeDecodeCliTest, FullStreamIsNearLossless) {
  TempDir dir;
  const auto in = testing::SampleMesh("holes.off");
  auto r = RunCli({"encode", in.string(), (dir / "holes.mwv").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("semi-regular, 2 levels"), std::string::npos) << r.err;
  r = RunCli({"decode", (dir / "holes.mwv").string(), (dir / "full.ply").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_GE(PsnrAgainst(in, dir / "full.ply"), 90.0);
}

// --threads: the same stream from one thread or several, for a remeshed
// mesh (elephant.off) and a semi-regular one; --help says so.
// The stream ends in the user's own mesh (docs/FORMAT.md 2.5): the same
// faces over the same vertex ids, every coordinate within half the
// precision's step; `--no-original` ends it in the remesh.
TEST(EncodeDecodeCliTest, CompleteStreamGivesBackTheInputsOwnMesh) {
  TempDir dir;
  const auto in = testing::SampleMesh("elephant.off");
  auto r = RunCli({"encode", in.string(), (dir / "e.mwv").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("original layer: 2775 vertices, 5558 faces"), std::string::npos) << r.out;
  // OBJ keeps every double exactly.
  r = RunCli({"decode", (dir / "e.mwv").string(), (dir / "e.obj").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto input = ReadMesh(in);
  auto decoded = ReadMesh(dir / "e.obj");
  ASSERT_TRUE(input.ok() && decoded.ok());
  ASSERT_EQ(decoded->positions.size(), input->positions.size());
  auto key = [](Face f) {
    std::rotate(f.begin(), std::min_element(f.begin(), f.end()), f.end());
    return f;
  };
  std::vector<Face> a, b;
  for (const Face& f : input->faces) a.push_back(key(f));
  for (const Face& f : decoded->faces) b.push_back(key(f));
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  EXPECT_EQ(a, b);
  Vec3 lo = input->positions[0], hi = lo;
  for (const Vec3& p : input->positions) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double half_step = std::ldexp((hi - lo).norm(), -16) / 2 * (1 + 1e-9);
  for (size_t v = 0; v < input->positions.size(); ++v) {
    ASSERT_LE((decoded->positions[v] - input->positions[v]).cwiseAbs().maxCoeff(), half_step)
        << "vertex " << v;
  }
  // Nothing lost on the way, packet by packet in the rd order: the remesh
  // complete, then the original's coarse positions, then each plane, each
  // at least as close to the input (symmetric surface PSNR).
  const std::string bytes = testing::ReadBytes(dir / "e.mwv");
  auto parsed = ParseContainer(bytes);
  ASSERT_TRUE(parsed.ok()) << parsed.status().ToString();
  auto d = ProgressiveDecoder::Create(parsed->header);
  ASSERT_TRUE(d.ok());
  double previous = 0;
  const std::vector<uint32_t> order = PacketOrder(parsed->header, Progression::kRd);
  const size_t layer = order.size() - 2 - parsed->header.original->refinement_planes;
  for (size_t i = 0; i < order.size(); ++i) {
    const uint32_t id = order[i];
    ASSERT_TRUE((*d)->AddPacket(id, parsed->payloads[id]).ok()) << id;
    if (i + 1 < layer) continue;  // within the remesh: the rd table's business
    const TriMesh shown = (*d)->OriginalReady() ? (*d)->OriginalMesh() : (*d)->Mesh();
    auto distance = SymmetricSurfaceDistance(*input, shown);
    ASSERT_TRUE(distance.ok());
    const double psnr = distance->PsnrDb(distance->rms);
    EXPECT_GE(psnr, previous - 0.05) << "after packet " << id;
    previous = psnr;
  }
  // Without the layer: the remesh, more vertices than the input.
  r = RunCli({"encode", in.string(), (dir / "n.mwv").string(), "--no-original"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.find("original layer"), std::string::npos) << r.out;
  r = RunCli({"decode", (dir / "n.mwv").string(), (dir / "n.ply").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto remesh = ReadMesh(dir / "n.ply");
  ASSERT_TRUE(remesh.ok());
  EXPECT_GT(remesh->positions.size(), input->positions.size());
}

TEST(EncodeDecodeCliTest, ThreadCountDoesNotChangeTheStream) {
  TempDir dir;
  for (const char* name : {"elephant.off", "holes.off"}) {
    const auto in = testing::SampleMesh(name);
    std::string first;
    for (const char* threads : {"1", "2", "3", "0"}) {
      const auto out = dir / (std::string(name) + "." + threads + ".mwv");
      auto r = RunCli({"encode", in.string(), out.string(), "--threads", threads});
      ASSERT_EQ(r.exit_code, 0) << r.err;
      const std::string bytes = testing::ReadBytes(out);
      ASSERT_FALSE(bytes.empty());
      if (first.empty()) first = bytes;
      EXPECT_TRUE(bytes == first) << name << " with --threads " << threads;
    }
  }
  for (const char* command : {"encode", "remesh"}) {
    auto help = RunCli({command, "--help"});
    EXPECT_EQ(help.exit_code, 0);
    EXPECT_NE(help.out.find("--threads"), std::string::npos) << command;
  }
  EXPECT_NE(RunCli({"encode", testing::SampleMesh("holes.off").string(),
                    (dir / "x.mwv").string(), "--threads", "-1"})
                .exit_code,
            0);
}

// --transform sawt end to end: the filter choices travel in the header and
// the complete stream is as near-lossless as the default transform's.
TEST(EncodeDecodeCliTest, SawtStreamIsNearLosslessLikeTheDefault) {
  TempDir dir;
  const auto in = testing::SampleMesh("holes.off");
  auto r = RunCli({"encode", in.string(), (dir / "sawt.mwv").string(), "--transform", "sawt",
                   "--sawt-alpha", "200"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("sawt/none"), std::string::npos) << r.out;  // unlifted by default
  EXPECT_NE(r.out.find("choices per filter f1:"), std::string::npos) << r.out;
  ASSERT_EQ(RunCli({"encode", in.string(), (dir / "bf.mwv").string()}).exit_code, 0);
  r = RunCli({"decode", (dir / "sawt.mwv").string(), (dir / "sawt.ply").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_EQ(RunCli({"decode", (dir / "bf.mwv").string(), (dir / "bf.ply").string()}).exit_code,
            0);
  const double sawt = PsnrAgainst(in, dir / "sawt.ply");
  const double butterfly = PsnrAgainst(in, dir / "bf.ply");
  EXPECT_GE(sawt, 90.0);
  EXPECT_GT(sawt, butterfly - 1.0) << "default " << butterfly;
  r = RunCli({"encode", "--help"});
  EXPECT_NE(r.out.find("sawt"), std::string::npos);
  EXPECT_NE(r.out.find("--sawt-alpha"), std::string::npos);
}

TEST(EncodeDecodeCliTest, BudgetAndMaxLevelGiveCoarserMeshes) {
  TempDir dir;
  const auto in = testing::SampleMesh("holes.off");
  // The remesh's prefixes: without the original layer, whose bytes would
  // be most of a semi-regular input's payload.
  ASSERT_EQ(RunCli({"encode", in.string(), (dir / "h.mwv").string(), "--no-original"}).exit_code,
            0);
  // A budget of the header plus a quarter of the payload.
  const std::string bytes = testing::ReadBytes(dir / "h.mwv");
  ASSERT_GT(bytes.size(), 8u);
  uint32_t header = 0;
  for (int i = 7; i >= 4; --i) header = header << 8 | static_cast<uint8_t>(bytes[i]);
  const size_t payload = bytes.size() - 8 - header;
  auto r = RunCli({"decode", (dir / "h.mwv").string(), (dir / "part.ply").string(),
                   "--budget", std::to_string(8 + header + payload / 4)});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const double part = PsnrAgainst(in, dir / "part.ply");
  EXPECT_LT(part, 90.0);
  EXPECT_GT(part, 40.0);

  r = RunCli({"decode", (dir / "h.mwv").string(), (dir / "l1.obj").string(),
              "--order", "resolution", "--max-level", "1"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto l1 = ReadMesh(dir / "l1.obj");
  ASSERT_TRUE(l1.ok());
  EXPECT_EQ(l1->faces.size(), 518u * 4);  // base 518 faces, one level

  r = RunCli({"decode", (dir / "h.mwv").string(), (dir / "x.ply").string(),
              "--budget", "10"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("smaller than the stream header"), std::string::npos) << r.err;
}

// A prefix of the resolution order that holds only the first level's
// details: by default the mesh goes one level past them (their smoothing
// subdivision), --extra-levels 0 stops at them, --extra-levels 12 writes
// every level.
TEST(EncodeDecodeCliTest, ExtraLevelsSetHowFarPastTheDetailsTheMeshGoes) {
  TempDir dir;
  const auto in = testing::SampleMesh("holes.off");  // 2 levels over 518 base faces
  // The whole base in the header: every payload byte of the budget is detail.
  ASSERT_EQ(RunCli({"encode", in.string(), (dir / "h.mwv").string(), "--base-refinement", "0",
                    "--no-original"})
                .exit_code,
            0);
  const std::string bytes = testing::ReadBytes(dir / "h.mwv");
  uint32_t header = 0;
  for (int i = 7; i >= 4; --i) header = header << 8 | static_cast<uint8_t>(bytes[i]);
  const size_t payload = bytes.size() - 8 - header;
  auto decode = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = {"decode", "--json", "--order", "resolution", "--budget",
                                     std::to_string(8 + header + payload / 8),
                                     (dir / "h.mwv").string(), (dir / "out.ply").string()};
    args.insert(args.end(), extra.begin(), extra.end());
    auto r = RunCli(args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    proto::DecodeReport report;
    EXPECT_TRUE(google::protobuf::util::JsonStringToMessage(r.out, &report).ok()) << r.out;
    auto mesh = ReadMesh(dir / "out.ply");
    EXPECT_TRUE(mesh.ok());
    if (mesh.ok()) {
      EXPECT_EQ(report.faces(), mesh->faces.size());
    }
    return report;
  };
  const proto::DecodeReport details = decode({"--extra-levels", "0"});
  EXPECT_EQ(details.level(), 1);
  EXPECT_EQ(details.faces(), 518u * 4);
  const proto::DecodeReport smoothed = decode({});
  EXPECT_EQ(smoothed.level(), 2);
  EXPECT_EQ(smoothed.faces(), 518u * 16);
  EXPECT_EQ(decode({"--extra-levels", "12"}).faces(), 518u * 16);
  // The whole stream has detail at every level: the same mesh whatever the extra.
  auto r = RunCli({"decode", "--json", "--extra-levels", "0", (dir / "h.mwv").string(),
                   (dir / "all.ply").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  proto::DecodeReport all;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(r.out, &all).ok()) << r.out;
  EXPECT_EQ(all.level(), 2);
}

// --fidelity: the sample's default remesh reaches 57 dB against it; asked
// for 65, encode remeshes denser and says what the complete stream reached,
// which `meshwave compare` on the decoded stream confirms. Out of reach
// (a density limit too low), it warns and still writes the stream.
TEST(EncodeDecodeCliTest, FidelityIsReachedAndReported) {
  TempDir dir;
  const auto in = testing::SampleMesh("elephant.off");
  auto r = RunCli({"encode", in.string(), (dir / "e.mwv").string(), "--fidelity", "65"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string key = "the complete stream is at ";
  const size_t at = r.out.find(key);
  ASSERT_NE(at, std::string::npos) << r.out;
  const double reported = std::stod(r.out.substr(at + key.size()));
  EXPECT_GE(reported, 65.0);
  ASSERT_EQ(RunCli({"decode", (dir / "e.mwv").string(), (dir / "e.ply").string()}).exit_code, 0);
  r = RunCli({"compare", in.string(), (dir / "e.ply").string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  proto::CompareReport compare;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(r.out, &compare).ok()) << r.out;
  EXPECT_GE(compare.surface().rms().psnr_db(), 65.0);
  EXPECT_NEAR(compare.surface().rms().psnr_db(), reported, 0.5);  // float32 PLY vs in memory

  // Beyond what the remesh reaches: the original layer reaches it; without
  // the layer, a warning says why the stream stops short.
  r = RunCli({"encode", in.string(), (dir / "f.mwv").string(), "--fidelity", "100",
              "--max-vertex-ratio", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const size_t f = r.out.find(key);
  ASSERT_NE(f, std::string::npos) << r.out;
  EXPECT_GE(std::stod(r.out.substr(f + key.size())), 100.0) << r.out;
  r = RunCli({"encode", in.string(), (dir / "g.mwv").string(), "--fidelity", "100",
              "--max-vertex-ratio", "2", "--no-original"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("fidelity 100.00 dB not reached: the remesh reached the density limit"),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "g.mwv"));
}

TEST(EncodeDecodeCliTest, JsonReportDescribesTheDecode) {
  TempDir dir;
  const auto in = testing::SampleMesh("holes.off");
  ASSERT_EQ(RunCli({"encode", in.string(), (dir / "h.mwv").string()}).exit_code, 0);
  const size_t size = testing::ReadBytes(dir / "h.mwv").size();
  auto r = RunCli({"decode", "--json", "--order", "rd", "--budget", std::to_string(size / 2),
                   (dir / "h.mwv").string(), (dir / "half.ply").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  proto::DecodeReport report;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(r.out, &report).ok()) << r.out;
  auto mesh = ReadMesh(dir / "half.ply");
  ASSERT_TRUE(mesh.ok());
  EXPECT_EQ(report.vertices(), mesh->positions.size());
  EXPECT_EQ(report.faces(), mesh->faces.size());
  EXPECT_EQ(report.order(), "rd");
  EXPECT_EQ(report.level(), 2);
  EXPECT_LE(report.bytes(), size / 2);
  EXPECT_GT(report.packets(), 0u);
  EXPECT_LT(report.packets(), report.packets_total());
  EXPECT_GT(report.decode_ms(), 0);
  // The index's estimate (error off the surface at the vertices) against
  // the surface PSNR (holes.off is encoded as it is): never optimistic by
  // more than a hair, and pessimistic by at most a few dB, as the surface
  // between vertices interpolates their errors (measured: 4.9 dB here).
  const double surface_db = PsnrAgainst(in, dir / "half.ply");
  EXPECT_LE(report.estimated_psnr_db(), surface_db + 1.0);
  EXPECT_GE(report.estimated_psnr_db(), surface_db - 6.0);
}

TEST(EncodeDecodeCliTest, DamagedStreamsAreRefusedOrDecodedPartly) {
  TempDir dir;
  ASSERT_EQ(RunCli({"encode", testing::SampleMesh("holes.off").string(),
                    (dir / "h.mwv").string()})
                .exit_code,
            0);
  std::string bytes = testing::ReadBytes(dir / "h.mwv");
  {
    std::ofstream f(dir / "cut.mwv", std::ios::binary);
    f.write(bytes.data(), static_cast<std::streamsize>(bytes.size() - 100));
  }
  auto r = RunCli({"decode", (dir / "cut.mwv").string(), (dir / "cut.ply").string()});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("cut short"), std::string::npos) << r.err;

  bytes[bytes.size() - 50] ^= 0x5a;
  {
    std::ofstream f(dir / "bad.mwv", std::ios::binary);
    f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  r = RunCli({"decode", (dir / "bad.mwv").string(), (dir / "bad.ply").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("CRC-16"), std::string::npos) << r.err;

  {
    std::ofstream f(dir / "junk.mwv", std::ios::binary);
    f << "not a stream at all";
  }
  r = RunCli({"decode", (dir / "junk.mwv").string(), (dir / "junk.ply").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("magic"), std::string::npos) << r.err;
}

TEST(EncodeDecodeCliTest, SimAndLinearOptionsWork) {
  TempDir dir;
  const auto in = testing::SampleMesh("holes.off");
  auto r = RunCli({"encode", in.string(), (dir / "s.mwv").string(), "--coder", "sim",
                   "--predictor", "linear", "--update", "none"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("linear/none sim"), std::string::npos) << r.out;
  ASSERT_EQ(RunCli({"decode", (dir / "s.mwv").string(), (dir / "s.ply").string()}).exit_code, 0);
  EXPECT_GE(PsnrAgainst(in, dir / "s.ply"), 90.0);
  r = RunCli({"encode", in.string(), (dir / "t.mwv").string(), "--coder", "zip"});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("zip"), std::string::npos) << r.err;
}

// A textured stream (format version 9, made with EncodeMesh: the CLI's
// encoder does not bake textures): info lists its maps, decode writes the
// texture into glTF and says in one line that PLY leaves it out.
TEST(EncodeDecodeCliTest, TexturedStreamInfoAndDecode) {
  TempDir dir;
  TriMesh octahedron;
  octahedron.positions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  octahedron.faces = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                      {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  auto mesh = Subdivide(octahedron, 2, SubdivisionScheme::kMidpoint);
  ASSERT_TRUE(mesh.ok());
  VertexAttributes attributes;
  BakedTexture texture;
  texture.atlas = {16, 1, 2};  // 4 cells: 32 x 32 texels
  texture.maps.push_back({TextureRole::kBaseColor, "image/png",
                          {testing::SolidPng(16, 16, 250, 0, 0), testing::SolidPng(32, 32, 0, 250, 0)}});
  attributes.texture = texture;
  auto stream = EncodeMesh(*mesh, EncodeOptions{}, attributes);
  ASSERT_TRUE(stream.ok()) << stream.status().ToString();
  const auto mwv = dir / "oct.mwv";
  {
    std::ofstream out(mwv, std::ios::binary);
    out << SerializeFullContainer(*stream);
  }
  auto info = RunCli({"info", mwv.string()});
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("format version 11"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("texture map:            base colour, image/png, 2 levels: 16 x 16"),
            std::string::npos)
      << info.out;
  auto glb = RunCli({"decode", mwv.string(), (dir / "oct.glb").string()});
  ASSERT_EQ(glb.exit_code, 0) << glb.err;
  EXPECT_NE(glb.out.find("textured: base colour 32 x 32"), std::string::npos) << glb.out;
  EXPECT_EQ(glb.err, "");
  const std::string bytes = testing::ReadBytes(dir / "oct.glb");
  EXPECT_NE(bytes.find(R"("mimeType":"image/png")"), std::string::npos);
  EXPECT_NE(bytes.find(testing::SolidPng(32, 32, 0, 250, 0)), std::string::npos);
  auto ply = RunCli({"decode", mwv.string(), (dir / "oct.ply").string()});
  ASSERT_EQ(ply.exit_code, 0) << ply.err;
  EXPECT_NE(ply.err.find("texture is not written"), std::string::npos) << ply.err;
  EXPECT_EQ(std::count(ply.err.begin(), ply.err.end(), '\n'), 1);
}

}  // namespace
}  // namespace meshwave
