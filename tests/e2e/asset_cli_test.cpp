// End-to-end: glTF into the CLI. The .glb that `meshwave decode` writes
// reads back (`info`, `encode`), `info` describes a file's attributes (text
// and JSON), a missing texture leaves the geometry described, `encode`
// names in one line what the stream leaves out, and every bad input is an
// error that writes nothing.
#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "codec/image/png_encoder_testonly.h"
#include "e2e/cli_runner.h"
#include "e2e/mesh_info_testonly.h"
#include "meshwave.pb.h"
#include "meshwave/mesh_asset.h"
#include "pipeline/color_transfer.h"

namespace meshwave {
namespace {

using testing::InfoOf;
using testing::RunCli;
using testing::TempDir;

void WriteText(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}


TEST(AssetCliTest, TheGlbThatDecodeWritesReadsBack) {
  TempDir dir;
  const auto in = testing::SampleMesh("holes.off");
  ASSERT_EQ(RunCli({"encode", in.string(), (dir / "h.mwv").string()}).exit_code,
            0);
  for (const char* out : {"h.glb", "h.gltf"}) {
    auto r = RunCli({"decode", (dir / "h.mwv").string(), (dir / out).string()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const proto::MeshInfo glb = InfoOf(dir / out);
    r = RunCli({"decode", (dir / "h.mwv").string(), (dir / "h.ply").string()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const proto::MeshInfo ply = InfoOf(dir / "h.ply");
    EXPECT_EQ(glb.format(), std::string(out).substr(2)) << out;
    EXPECT_EQ(glb.cleaned().DebugString(), ply.cleaned().DebugString()) << out;
    EXPECT_EQ(glb.semiregular_levels(), ply.semiregular_levels()) << out;
    EXPECT_EQ(glb.asset().uv_values(), 0u);
    EXPECT_TRUE(glb.asset().error().empty()) << glb.asset().error();
    // encode takes it as input.
    r = RunCli({"encode", (dir / out).string(), (dir / "again.mwv").string()});
    EXPECT_EQ(r.exit_code, 0) << r.err;
  }
}

TEST(AssetCliTest, InfoDescribesAttributes) {
  const auto ring = testing::SampleDataDir() / "textured/ring.glb";
  const proto::MeshInfo info = InfoOf(ring);
  EXPECT_EQ(info.format(), "glb");
  EXPECT_EQ(info.asset().uv_values(), 626u);
  EXPECT_EQ(info.asset().color_values(), 626u);
  ASSERT_EQ(info.asset().materials_size(), 2);
  EXPECT_EQ(info.asset().materials(0), "checker");
  ASSERT_EQ(info.asset().images_size(), 1);
  EXPECT_EQ(info.asset().images(0).width(), 128u);
  EXPECT_EQ(info.asset().images(0).mime_type(), "image/png");

  const auto r = RunCli(
      {"info", (testing::SampleDataDir() / "textured/die.obj").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(
      r.out.find(
          "attributes:             UVs (1014 values), no vertex colours; 1 "
          "material: \"die\" (base colour texture); 1 image: die.png PNG "
          "192x128. Notes: die.mtl: Ks not carried"),
      std::string::npos)
      << r.out;
}

TEST(AssetCliTest, AMissingTextureLeavesTheGeometryDescribed) {
  TempDir dir;
  for (const char* name : {"die.obj", "die.mtl"}) {
    std::filesystem::copy_file(testing::SampleDataDir() / "textured" / name,
                               dir / name);
  }
  const auto r = RunCli({"info", (dir / "die.obj").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("faces:                  1728"), std::string::npos)
      << r.out;
  EXPECT_NE(
      r.out.find(
          "attributes:             not readable: not found: die.obj: texture "
          "die.png is missing"),
      std::string::npos)
      << r.out;
}

TEST(AssetCliTest, EncodeNamesWhatTheStreamLeavesOut) {
  TempDir dir;
  const auto ring = testing::SampleDataDir() / "textured/ring.glb";
  auto r = RunCli({"encode", ring.string(), (dir / "ring.mwv").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Its UVs, two materials, texture and colours are baked: nothing left
  // to name, and the maps are listed.
  EXPECT_EQ(r.err.find("not coded"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("texture: atlas "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("base colour"), std::string::npos) << r.out;

  // Vertex colours are coded: nothing left to name.
  const auto ball = testing::SampleDataDir() / "textured/hue_ball.ply";
  r = RunCli({"encode", ball.string(), (dir / "ball.mwv").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("not coded"), std::string::npos) << r.err;
  EXPECT_EQ(r.out.find("texture: "), std::string::npos) << r.out;

  // UVs without a texture: named.
  {
    std::ofstream obj(dir / "uv.obj");
    obj << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvt 0 0\nvt 1 0\nvt 0 1\n"
           "f 1/1 3/3 2/2\nf 1/1 2/2 4/3\nf 1/1 4/3 3/3\nf 2/2 3/3 4/3\n";
  }
  r = RunCli({"encode", (dir / "uv.obj").string(), (dir / "uv.mwv").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("uv.obj: the stream holds the geometry; not coded: UVs (no texture "
                       "uses them)"),
            std::string::npos)
      << r.err;

  // A texture that cannot be read: an error that says what is missing and
  // what would encode the geometry alone; nothing is written.
  for (const char* name : {"die.obj", "die.mtl"}) {
    std::filesystem::copy_file(testing::SampleDataDir() / "textured" / name,
                               dir / name);
  }
  r = RunCli({"encode", (dir / "die.obj").string(), (dir / "die.mwv").string()});
  EXPECT_NE(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("texture die.png is missing"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--allow-geometry-only"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "die.mwv"));

  // Asked for: the geometry is encoded, and said so.
  r = RunCli({"encode", "--allow-geometry-only", (dir / "die.obj").string(),
              (dir / "die.mwv").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("die.obj: the stream holds the geometry only; the "
                       "file's attributes could not be read (not found: "
                       "die.obj: texture die.png is missing"),
            std::string::npos)
      << r.err;

  // Geometry alone: nothing to name.
  r = RunCli({"encode", testing::SampleMesh("holes.off").string(),
              (dir / "holes.mwv").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("not coded"), std::string::npos) << r.err;
}

// Per vertex of the asset's mesh, the colour of a corner at it (the
// writers give one colour per vertex). Empty without colours.
std::vector<Vec3> VertexColors(const MeshAsset& asset) {
  std::vector<Vec3> out;
  if (asset.color.empty()) return out;
  out.assign(asset.mesh.positions.size(), Vec3::Zero());
  for (size_t f = 0; f < asset.mesh.faces.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      out[asset.mesh.faces[f][k]] =
          asset.color.values[asset.color.faces[f][k]].head<3>().cast<double>();
    }
  }
  return out;
}

double ColorPsnr(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double sse = 0;
  for (size_t i = 0; i < a.size(); ++i) sse += (a[i] - b[i]).squaredNorm();
  return 10 * std::log10(static_cast<double>(3 * a.size()) / std::max(sse, 1e-30));
}

TEST(AssetCliTest, ColouredPlyDecodesToItsColours) {
  TempDir dir;
  const auto ball = testing::SampleDataDir() / "textured/hue_ball.ply";
  auto r = RunCli({"encode", ball.string(), (dir / "ball.mwv").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("colour channel: "), std::string::npos) << r.out;
  const Result<MeshAsset> original = ReadMeshAsset(ball);
  ASSERT_TRUE(original.ok()) << original.status().ToString();
  // Against the original's colour at the nearest point of its surface.
  auto expected = [&](const MeshAsset& decoded) {
    auto c = TransferCornerColors(original->mesh.positions, original->mesh.faces, original->color,
                                  decoded.mesh.positions);
    EXPECT_TRUE(c.ok());
    return *c;
  };
  // The whole stream, then a prefix: colours travel in both.
  r = RunCli({"decode", (dir / "ball.mwv").string(), (dir / "ball.ply").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("with vertex colours"), std::string::npos) << r.out;
  const Result<MeshAsset> ply = ReadMeshAsset(dir / "ball.ply");
  ASSERT_TRUE(ply.ok()) << ply.status().ToString();
  const std::vector<Vec3> colors = VertexColors(*ply);
  ASSERT_EQ(colors.size(), ply->mesh.positions.size()) << "colours dropped";
  // Measured 76.5 dB (the PLY's 8-bit sRGB colours come back to their
  // bytes); a grey mesh scores 9.8 dB.
  EXPECT_GT(ColorPsnr(colors, expected(*ply)), 65.0);
  EXPECT_LT(ColorPsnr(std::vector<Vec3>(colors.size(), Vec3::Constant(0.5)), expected(*ply)),
            15.0);

  // COLOR_0 (floats) of the whole stream (3,805 bytes; measured 70.0 dB)
  // and of a 2,500-byte rd prefix (44.8 dB).
  for (const auto& [budget, least] : {std::pair<const char*, double>{"8000", 65.0}, {"2500", 40.0}}) {
    SCOPED_TRACE(budget);
    r = RunCli({"decode", (dir / "ball.mwv").string(), (dir / "ball.glb").string(), "--budget",
                budget, "--order", "rd"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Result<MeshAsset> glb = ReadMeshAsset(dir / "ball.glb");
    ASSERT_TRUE(glb.ok()) << glb.status().ToString();
    const std::vector<Vec3> decoded = VertexColors(*glb);
    ASSERT_EQ(decoded.size(), glb->mesh.positions.size()) << "COLOR_0 dropped";
    EXPECT_GT(ColorPsnr(decoded, expected(*glb)), least);
  }
}

}  // namespace
}  // namespace meshwave

namespace meshwave {
namespace {

// The bad inputs a user may hand over, each through `meshwave encode`: a
// clear message naming the problem, a failing exit, and no stream written.
TEST(AssetCliTest, EveryBadInputIsAnErrorAndWritesNothing) {
  TempDir dir;
  const auto textured = testing::SampleDataDir() / "textured";
  struct Case {
    std::string name, main, message;
  };
  std::vector<Case> cases;
  auto folder = [&](const std::string& name) {
    std::filesystem::create_directories(dir / name);
    return dir / name;
  };
  {  // A decompression bomb: a PNG declaring 20000 x 20000 pixels.
    const auto d = folder("bomb");
    std::filesystem::copy_file(textured / "die.obj", d / "die.obj");
    std::filesystem::copy_file(textured / "die.mtl", d / "die.mtl");
    WriteText(d / "die.png", testing::BombPng(20000, 20000));
    cases.push_back({"bomb", (d / "die.obj").string(), "PNG declares 20000x20000"});
  }
  {  // A missing image.
    const auto d = folder("missing");
    std::filesystem::copy_file(textured / "die.obj", d / "die.obj");
    std::filesystem::copy_file(textured / "die.mtl", d / "die.mtl");
    cases.push_back({"missing image", (d / "die.obj").string(), "texture die.png is missing"});
  }
  {  // A UV index out of range.
    const auto d = folder("uv");
    WriteText(d / "uv.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvt 0 0\nvt 1 0\n"
                            "f 1/1 3/2 2/1\nf 1/1 2/2 4/9\nf 1/1 4/1 3/2\nf 2/1 3/2 4/1\n");
    cases.push_back({"UV index", (d / "uv.obj").string(),
                     "uv.obj: line 8: texture coordinate index 9 out of range"});
  }
  {  // A truncated buffer: half of a .glb.
    const auto d = folder("truncated");
    const std::string glb = testing::ReadBytes(textured / "ring.glb");
    ASSERT_GT(glb.size(), 100u);
    WriteText(d / "ring.glb", glb.substr(0, glb.size() / 2));
    cases.push_back({"truncated buffer", (d / "ring.glb").string(), "ring.glb: truncated"});
  }
  {  // NaN coordinates.
    const auto d = folder("nan");
    WriteText(d / "nan.obj", "v 0 0 0\nv 1 0 0\nv nan 1 0\nv 0 0 1\n"
                             "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
    cases.push_back({"NaN", (d / "nan.obj").string(),
                     "nan.obj: line 3: coordinate \"nan\" is NaN or infinite"});
  }
  for (const Case& c : cases) {
    const auto out = dir / (c.name + ".mwv");
    const auto r = RunCli({"encode", c.main, out.string()});
    EXPECT_NE(r.exit_code, 0) << c.name << ": " << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.name << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << c.name;
  }
}

}  // namespace
}  // namespace meshwave
