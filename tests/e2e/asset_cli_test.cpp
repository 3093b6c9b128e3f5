// End-to-end: glTF into the CLI. The .glb that `meshwave decode` writes
// reads back (`info`, `encode`), `info` describes a file's attributes (text
// and JSON), a missing texture leaves the geometry described, and `encode`
// names in one line what the stream leaves out.
#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "e2e/cli_runner.h"
#include "e2e/mesh_info_testonly.h"
#include "meshwave.pb.h"

namespace meshwave {
namespace {

using testing::InfoOf;
using testing::RunCli;
using testing::TempDir;

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
  EXPECT_NE(r.err.find("warning: " + ring.string() +
                       ": the stream holds the geometry only; not coded yet: "
                       "UVs, vertex colours, 2 materials, 1 texture image\n"),
            std::string::npos)
      << r.err;

  const auto ball = testing::SampleDataDir() / "textured/hue_ball.ply";
  r = RunCli({"encode", ball.string(), (dir / "ball.mwv").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find(ball.string() +
                       ": the stream holds the geometry only; not coded yet: "
                       "vertex colours\n"),
            std::string::npos)
      << r.err;

  // A texture that cannot be read: the geometry is encoded, and said so.
  for (const char* name : {"die.obj", "die.mtl"}) {
    std::filesystem::copy_file(testing::SampleDataDir() / "textured" / name,
                               dir / name);
  }
  r = RunCli({"encode", (dir / "die.obj").string(), (dir / "die.mwv").string()});
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
  EXPECT_EQ(r.err.find("not coded yet"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace meshwave
