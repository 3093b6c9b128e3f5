// Coloured PLY as an asset: colour properties of any type and spelling, in
// every encoding, decoded from sRGB to linear; the geometry exactly what
// ReadMesh reads (then welded); what else the file holds noted.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <string>

#include "codec/asset/asset_checks_testonly.h"
#include "mesh/ply_header.h"
#include "meshwave/file_set.h"
#include "meshwave/mesh_asset.h"
#include "meshwave/mesh_io.h"

namespace meshwave {
namespace {

using ::testing::HasSubstr;

Result<MeshAsset> ParsePlyAsset(const std::string& bytes) {
  return testing::ParseInMemory("c.ply", bytes);
}

constexpr char kAsciiHeader[] =
    "ply\nformat ascii 1.0\nelement vertex 3\n"
    "property float x\nproperty float y\nproperty float z\n";

TEST(PlyAssetTest, ReadsUcharColoursAsLinearRgba) {
  const std::string ply =
      std::string(kAsciiHeader) +
      "property uchar red\nproperty uchar green\n"
      "property uchar blue\nproperty uchar alpha\n"
      "element face 1\nproperty list uchar int vertex_indices\n"
      "end_header\n"
      "0 0 0 255 0 0 255\n1 0 0 0 128 0 128\n0 1 0 0 0 0 0\n"
      "3 0 1 2\n";
  const auto asset = ParsePlyAsset(ply);
  ASSERT_TRUE(asset.ok()) << asset.status().ToString();
  ASSERT_EQ(asset->color.values.size(), 3u);
  EXPECT_EQ(asset->color.values[0], Eigen::Vector4f(1, 0, 0, 1));
  EXPECT_NEAR(asset->color.values[1].y(), 0.2158605, 1e-6);   // sRGB 128/255
  EXPECT_FLOAT_EQ(asset->color.values[1].w(), 128.0f / 255);  // alpha: linear
  EXPECT_EQ(asset->color.values[2], Eigen::Vector4f(0, 0, 0, 0));
  EXPECT_EQ(asset->color.faces, asset->mesh.faces);
  EXPECT_TRUE(asset->uv.empty());
  EXPECT_TRUE(asset->notes.empty());
}

TEST(PlyAssetTest, ReadsUshortFloatAndDiffuseSpellingsWithoutAlpha) {
  const std::string ply =
      std::string(kAsciiHeader) +
      "property ushort diffuse_red\nproperty float diffuse_green\n"
      "property double diffuse_blue\nproperty float nx\n"
      "property float quality\n"
      "element face 1\nproperty list uchar int vertex_indices\n"
      "property uchar flags\n"
      "element edge 0\nproperty int vertex1\n"
      "element material 1\nproperty float shine\n"
      "end_header\n"
      "0 0 0 65535 0.5 1 0 7\n1 0 0 0 2 -1 0 7\n0 1 0 0 0 0 0 7\n"
      "3 0 1 2 9\n0.5\n";
  const auto asset = ParsePlyAsset(ply);
  ASSERT_TRUE(asset.ok()) << asset.status().ToString();
  EXPECT_EQ(asset->color.values[0].x(), 1.0f);
  EXPECT_NEAR(asset->color.values[0].y(), 0.2140, 1e-4);
  EXPECT_EQ(asset->color.values[0].z(), 1.0f);
  EXPECT_EQ(asset->color.values[0].w(), 1.0f);
  EXPECT_EQ(asset->color.values[1], Eigen::Vector4f(0, 1, 0, 1));  // clamped
  ASSERT_EQ(asset->notes.size(), 4u);
  EXPECT_THAT(asset->notes[0],
              HasSubstr("c.ply: vertex normals (nx) not carried"));
  EXPECT_THAT(asset->notes[1],
              HasSubstr("c.ply: vertex properties quality not carried"));
  EXPECT_THAT(asset->notes[2],
              HasSubstr("c.ply: face properties flags not carried"));
  EXPECT_THAT(asset->notes[3],
              HasSubstr("c.ply: elements material not carried"));
}

std::string BinaryColouredTriangle(std::endian order) {
  std::string out =
      std::string("ply\nformat ") +
      (order == std::endian::little ? "binary_little_endian"
                                    : "binary_big_endian") +
      " 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty ushort red\nproperty ushort green\n"
      "property ushort blue\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  auto put = [&](auto v) {
    char b[sizeof(v)];
    std::memcpy(b, &v, sizeof(v));
    if (order != std::endian::native) std::reverse(b, b + sizeof(v));
    out.append(b, sizeof(v));
  };
  for (int i = 0; i < 3; ++i) {
    put(static_cast<float>(i == 1));
    put(static_cast<float>(i == 2));
    put(0.0f);
    put(static_cast<uint16_t>(i == 0 ? 65535 : 0));
    put(static_cast<uint16_t>(i == 1 ? 65535 : 0));
    put(static_cast<uint16_t>(i == 2 ? 65535 : 0));
  }
  put(static_cast<uint8_t>(3));
  for (int32_t v : {0, 1, 2}) put(v);
  return out;
}

TEST(PlyAssetTest, ReadsBinaryColoursInBothByteOrders) {
  for (std::endian order : {std::endian::little, std::endian::big}) {
    const std::string ply = BinaryColouredTriangle(order);
    const auto asset = ParsePlyAsset(ply);
    ASSERT_TRUE(asset.ok()) << asset.status().ToString();
    EXPECT_EQ(asset->color.values[0], Eigen::Vector4f(1, 0, 0, 1));
    EXPECT_EQ(asset->color.values[1], Eigen::Vector4f(0, 1, 0, 1));
    EXPECT_EQ(asset->color.values[2], Eigen::Vector4f(0, 0, 1, 1));
    // The geometry is what ParseMesh reads.
    const auto mesh = ParseMesh(ply, MeshFormat::kPly, "c.ply");
    ASSERT_TRUE(mesh.ok());
    EXPECT_EQ(asset->mesh.positions, mesh->positions);
    EXPECT_EQ(asset->mesh.faces, mesh->faces);
  }
}

TEST(PlyAssetTest, ListPropertiesDoNotDisturbColours) {
  // A vertex element with a list: the record-by-record path.
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
      "property list uchar float extra\nproperty float y\nproperty float z\n"
      "property uchar red\nproperty uchar green\nproperty uchar blue\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 2 9 9 0 0 255 255 255\n1 0 0 0 0 0 0\n0 1 5 1 0 10 20 30\n3 0 1 2\n";
  const auto asset = ParsePlyAsset(ply);
  ASSERT_TRUE(asset.ok()) << asset.status().ToString();
  EXPECT_EQ(asset->color.values[1], Eigen::Vector4f(0, 0, 0, 1));
  EXPECT_EQ(asset->mesh.positions[2], Vec3(0, 1, 0));
  EXPECT_EQ(asset->color.values[0], Eigen::Vector4f(1, 1, 1, 1));
  EXPECT_THAT(asset->notes[0],
              HasSubstr("vertex properties extra not carried"));
}

TEST(PlyAssetTest, PartialColoursAreNotedAndNanColoursRefused) {
  const std::string partial =
      std::string(kAsciiHeader) +
      "property uchar red\nproperty uchar green\n"
      "element face 1\nproperty list uchar int vertex_indices\n"
      "end_header\n0 0 0 1 2\n1 0 0 1 2\n0 1 0 1 2\n3 0 1 2\n";
  const auto asset = ParsePlyAsset(partial);
  ASSERT_TRUE(asset.ok()) << asset.status().ToString();
  EXPECT_TRUE(asset->color.empty());
  EXPECT_THAT(
      asset->notes[0],
      HasSubstr("vertex properties red, green not carried (colours need red, "
                "green and blue)"));
  const std::string nan =
      std::string(kAsciiHeader) +
      "property float red\nproperty float green\nproperty float blue\n"
      "element face 1\nproperty list uchar int vertex_indices\n"
      "end_header\n0 0 0 1 1 1\n1 0 0 nan 1 1\n0 1 0 1 1 1\n3 0 1 2\n";
  const auto refused = ParsePlyAsset(nan);
  EXPECT_EQ(refused.status().code(), StatusCode::kParseError);
  EXPECT_THAT(refused.status().message(), HasSubstr("vertex 1: colour is NaN"));
}

TEST(PlyAssetTest, ColourChannelsScaleByTheirType) {
  EXPECT_FLOAT_EQ(PlyColorChannel(255, PlyScalar::kUint8), 1.0f);
  EXPECT_FLOAT_EQ(PlyColorChannel(51, PlyScalar::kUint8), 0.2f);
  EXPECT_FLOAT_EQ(PlyColorChannel(65535, PlyScalar::kUint16), 1.0f);
  EXPECT_FLOAT_EQ(PlyColorChannel(-5, PlyScalar::kInt8), 0.0f);
  EXPECT_FLOAT_EQ(PlyColorChannel(0.25, PlyScalar::kFloat32), 0.25f);
  EXPECT_FLOAT_EQ(PlyColorChannel(1.5, PlyScalar::kFloat64), 1.0f);
}

}  // namespace
}  // namespace meshwave
