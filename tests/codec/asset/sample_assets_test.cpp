// The project's own textured and coloured samples (data/textured/, made by
// tools/make_textured_samples.py): what each holds, that they are connected
// surfaces once welded, and that the script makes them again.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "meshwave/mesh.h"
#include "meshwave/mesh_asset.h"
#include "meshwave/mesh_stats.h"
#include "test_data.h"

namespace meshwave {
namespace {

std::filesystem::path Sample(const std::string& name) {
  return testing::SampleDataDir() / "textured" / name;
}

std::string Bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void ExpectClosedAndConnected(const TriMesh& mesh) {
  const MeshStats stats = ComputeStats(mesh);
  EXPECT_TRUE(stats.manifold);
  EXPECT_TRUE(stats.closed);
  EXPECT_EQ(stats.components, 1u);
}

TEST(SampleAssetsTest, DieIsATexturedObj) {
  const auto asset = ReadMeshAsset(Sample("die.obj"));
  ASSERT_TRUE(asset.ok()) << asset.status().ToString();
  EXPECT_EQ(asset->mesh.positions.size(), 866u);  // 6 grids of 13 x 13, welded
  EXPECT_EQ(asset->mesh.faces.size(), 1728u);
  EXPECT_EQ(asset->uv.values.size(), 1014u);  // every cube edge a seam
  ExpectClosedAndConnected(asset->mesh);
  ASSERT_EQ(asset->materials.size(), 1u);
  EXPECT_EQ(asset->materials[0].base_color_texture.wrap_u,
            WrapMode::kClampToEdge);
  ASSERT_EQ(asset->images.size(), 1u);
  EXPECT_EQ(asset->images[0].width, 192u);
  EXPECT_EQ(asset->images[0].height, 128u);
  // Face 1's centre: the middle of its atlas tile is a pip (dark).
  const auto& rgba = asset->images[0].rgba;
  const size_t centre = (32 * 192 + 32) * 4;
  EXPECT_LT(rgba[centre], 64);
}

TEST(SampleAssetsTest, RingIsATexturedAndColouredGlb) {
  const auto asset = ReadMeshAsset(Sample("ring.glb"));
  ASSERT_TRUE(asset.ok()) << asset.status().ToString();
  EXPECT_EQ(asset->mesh.positions.size(), 48u * 24);
  EXPECT_EQ(asset->mesh.faces.size(), 2u * 48 * 24);
  ExpectClosedAndConnected(asset->mesh);
  EXPECT_EQ(asset->uv.values.size(), 25u * 25 + 1);     // + the shared (0, 0)
  EXPECT_EQ(asset->color.values.size(), 25u * 25 + 1);  // + the shared white
  ASSERT_EQ(asset->materials.size(), 2u);
  EXPECT_EQ(asset->materials[0].name, "checker");
  EXPECT_FLOAT_EQ(asset->materials[0].base_color_texture.transform(0, 0), 2.0f);
  ASSERT_EQ(asset->images.size(), 1u);
  EXPECT_EQ(asset->images[0].width, 128u);
  EXPECT_TRUE(asset->notes.empty()) << asset->notes[0];
  // The nodes: scale 0.5 after a quarter turn about x; the ring lies in
  // the x-z plane, its tube radius 0.35 -> 0.175 in y.
  const Aabb box = BoundingBox(asset->mesh.positions);
  EXPECT_NEAR(box.max.x(), 0.5 * 1.35, 1e-6);
  EXPECT_NEAR(box.max.y() - box.min.y(), 0.35, 1e-6);
}

TEST(SampleAssetsTest, HueBallIsAColouredPly) {
  const auto asset = ReadMeshAsset(Sample("hue_ball.ply"));
  ASSERT_TRUE(asset.ok()) << asset.status().ToString();
  EXPECT_EQ(asset->mesh.positions.size(), 642u);
  EXPECT_EQ(asset->mesh.faces.size(), 1280u);
  ExpectClosedAndConnected(asset->mesh);
  ASSERT_EQ(asset->color.values.size(), 642u);
  size_t chromatic = 0;
  for (const auto& c : asset->color.values) chromatic += c.x() != c.y();
  EXPECT_GT(chromatic, 600u);
}

TEST(SampleAssetsTest, TheScriptMakesTheSamplesAgain) {
  if (std::system("python3 -c '' 2>/dev/null") != 0) {
    GTEST_SKIP() << "python3 is not installed: the samples' script cannot run";
  }
  const auto dir = std::filesystem::temp_directory_path() /
                   ("meshwave_samples_" + std::to_string(::getpid()));
  const std::string cmd =
      "python3 '" +
      (testing::SourceDir() / "tools/make_textured_samples.py").string() +
      "' '" + dir.string() + "' > /dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  // Byte for byte where zlib plays no part; the PNGs (and the .glb that
  // holds one) by what they decode to, as zlib's output may change between
  // its versions.
  for (const char* name : {"die.obj", "die.mtl", "hue_ball.ply"}) {
    EXPECT_EQ(Bytes(dir / name), Bytes(Sample(name))) << name;
  }
  for (const char* name : {"die.obj", "ring.glb"}) {
    const auto made = ReadMeshAsset(dir / name);
    const auto shipped = ReadMeshAsset(Sample(name));
    ASSERT_TRUE(made.ok() && shipped.ok()) << name;
    EXPECT_EQ(made->mesh.positions, shipped->mesh.positions) << name;
    EXPECT_EQ(made->uv.values, shipped->uv.values) << name;
    EXPECT_EQ(made->color.values, shipped->color.values) << name;
    ASSERT_EQ(made->images.size(), shipped->images.size()) << name;
    for (size_t i = 0; i < made->images.size(); ++i) {
      EXPECT_EQ(made->images[i].rgba, shipped->images[i].rgba) << name;
    }
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace meshwave
