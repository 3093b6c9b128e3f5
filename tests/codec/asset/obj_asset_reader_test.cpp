// The OBJ + MTL reader: texture coordinates (flipped to glTF's v), corner
// forms, materials and their textures with options, vertex colours, notes,
// and a message for every malformed input.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "codec/asset/asset_checks_testonly.h"
#include "codec/image/png_encoder_testonly.h"
#include "meshwave/file_set.h"
#include "meshwave/mesh_asset.h"

namespace meshwave {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

using testing::AnyNote;
using testing::ErrorOf;

Result<MeshAsset> ParseObj(const std::string& obj,
                           const testing::ExtraFiles& others = {}) {
  return testing::ParseInMemory("m.obj", obj, others);
}

std::string Png1x1() { return testing::EncodeRgbaPng(1, 1, {10, 20, 30, 255}); }

constexpr char kSquare[] =
    "mtllib m.mtl\n"
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
    "vn 0 0 1\n"
    "usemtl red\n"
    "f 1/1/1 2/2/1 3/3/1 4/4/1\n";

TEST(ObjAssetReaderTest, ReadsUvsFlippedToGltfConventionAndFanTriangulates) {
  const auto asset = ParseObj(kSquare, {{"m.mtl", "newmtl red\nKd 1 0 0\n"}});
  ASSERT_TRUE(asset.ok()) << asset.status().ToString();
  EXPECT_THAT(asset->mesh.faces, ElementsAre(Face{0, 1, 2}, Face{0, 2, 3}));
  ASSERT_EQ(asset->uv.values.size(), 4u);
  EXPECT_EQ(asset->uv.values[0], Eigen::Vector2f(0, 1));  // bottom-left
  EXPECT_EQ(asset->uv.values[2], Eigen::Vector2f(1, 0));  // top-right
  EXPECT_THAT(asset->uv.faces, ElementsAre(Face{0, 1, 2}, Face{0, 2, 3}));
  ASSERT_EQ(asset->materials.size(), 1u);
  EXPECT_EQ(asset->materials[0].name, "red");
  EXPECT_EQ(asset->materials[0].base_color_factor, Eigen::Vector4f(1, 0, 0, 1));
  EXPECT_FLOAT_EQ(asset->materials[0].metallic_factor, 0.0f);
  EXPECT_THAT(asset->face_material, ElementsAre(0u, 0u));
  EXPECT_TRUE(AnyNote(*asset, "m.obj: 1 vertex normals (vn) not carried"));
}

TEST(ObjAssetReaderTest, ReadsTheCornerFormsAndRelativeIndices) {
  const auto asset = ParseObj(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
      "f -3/-3 -2/-2 -1/-1\nf 1//1 2//1 3//1\nf 1 2 3\n");
  ASSERT_TRUE(asset.ok()) << asset.status().ToString();
  EXPECT_EQ(asset->mesh.faces.size(), 3u);
  // Faces without vt share a (0, 0) value, noted.
  ASSERT_EQ(asset->uv.values.size(), 4u);
  EXPECT_EQ(asset->uv.faces[1], (Face{3, 3, 3}));
  EXPECT_EQ(asset->uv.values[3], Eigen::Vector2f(0, 0));
  EXPECT_TRUE(
      AnyNote(*asset, "2 faces without texture coordinates get UV (0, 0)"));
  EXPECT_TRUE(asset->face_material.empty());
}

TEST(ObjAssetReaderTest, WeldsPositionsButKeepsUvSeams) {
  // Two triangles sharing an edge by position, with distinct vt.
  const auto asset = ParseObj(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
      "vt 0 0\nvt 1 0\nvt 0 1\nvt 0.5 0.5\nvt 0.6 0.6\nvt 0.7 0.7\n"
      "f 1/1 2/2 3/3\nf 4/4 6/6 5/5\n");
  ASSERT_TRUE(asset.ok()) << asset.status().ToString();
  EXPECT_EQ(asset->mesh.positions.size(), 4u);
  EXPECT_THAT(asset->mesh.faces, ElementsAre(Face{0, 1, 2}, Face{1, 3, 2}));
  EXPECT_THAT(asset->uv.faces, ElementsAre(Face{0, 1, 2}, Face{3, 5, 4}));
}

TEST(ObjAssetReaderTest, ReadsMtlTexturesWithTheirOptions) {
  const std::string mtl =
      "# exported\n"
      "newmtl wood\n"
      "Ka 1 1 1\nKd 0.8\nKs 0.5 0.5 0.5\nNs 20\nd 0.5\nTr 0.9\n"
      "map_Kd -s 2 3 -o 0.25 0.5 1 -clamp on textures\\wood grain.png\n"
      "map_Bump -bm 0.7 -imfchan l normal.png\n"
      "map_Ke glow.png\n"
      "Pr 0.3\nPm 0.6\n";
  const auto asset = ParseObj(
      "mtllib lib/m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nusemtl wood\nf 1/1 "
      "2/1 3/1\n",
      {{"lib/m.mtl", mtl},
       {"lib/textures/wood grain.png", Png1x1()},
       {"lib/normal.png", Png1x1()},
       {"lib/glow.png", Png1x1()}});
  ASSERT_TRUE(asset.ok()) << asset.status().ToString();
  const Material& m = asset->materials[0];
  EXPECT_EQ(m.base_color_factor, Eigen::Vector4f(0.8f, 0.8f, 0.8f, 0.5f));
  EXPECT_EQ(m.alpha_mode, AlphaMode::kBlend);
  EXPECT_FLOAT_EQ(m.roughness_factor, 0.3f);
  EXPECT_FLOAT_EQ(m.metallic_factor, 0.6f);
  ASSERT_EQ(asset->images.size(), 3u);
  EXPECT_EQ(asset->images[m.base_color_texture.image].name,
            "lib/textures/wood grain.png");
  EXPECT_EQ(m.base_color_texture.wrap_u, WrapMode::kClampToEdge);
  Eigen::Matrix<float, 2, 3> expected;
  expected << 2, 0, 0.25f, 0, 3, 1 - 3 - 0.5f;
  EXPECT_TRUE(m.base_color_texture.transform.isApprox(expected))
      << m.base_color_texture.transform;
  EXPECT_EQ(asset->images[m.normal_texture.image].name, "lib/normal.png");
  EXPECT_FLOAT_EQ(m.normal_scale, 0.7f);
  EXPECT_EQ(asset->images[m.emissive_texture.image].name, "lib/glow.png");
  EXPECT_EQ(m.emissive_factor, Eigen::Vector3f(1, 1, 1));
  EXPECT_EQ(asset->images[0].width, 1u);
  EXPECT_TRUE(AnyNote(*asset, "lib/m.mtl: Ka, Ks, Ns not carried"));
}

TEST(ObjAssetReaderTest, ReadsVertexColoursAsLinear) {
  const auto asset =
      ParseObj("v 0 0 0 1 0 0\nv 1 0 0 0 0.5 0\nv 0 1 0\nf 1 2 3\n");
  ASSERT_TRUE(asset.ok()) << asset.status().ToString();
  ASSERT_EQ(asset->color.values.size(), 3u);
  EXPECT_EQ(asset->color.values[0], Eigen::Vector4f(1, 0, 0, 1));
  EXPECT_NEAR(asset->color.values[1].y(), 0.2140, 1e-4);  // sRGB 0.5
  EXPECT_EQ(asset->color.values[2], Eigen::Vector4f(1, 1, 1, 1));
  EXPECT_THAT(asset->color.faces, ElementsAre(Face{0, 1, 2}));
}

TEST(ObjAssetReaderTest, NotesUndefinedMaterialsLinesAndPoints) {
  const auto asset = ParseObj(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nusemtl ghost\nf 1 3 2\nl 1 2\np "
      "3\n");
  ASSERT_TRUE(asset.ok()) << asset.status().ToString();
  EXPECT_THAT(asset->face_material, ElementsAre(1u, 0u));
  EXPECT_EQ(asset->materials[0].name, "ghost");
  EXPECT_EQ(asset->materials[1].name, "default");
  EXPECT_TRUE(
      AnyNote(*asset, "material \"ghost\" is defined in no material library"));
  EXPECT_TRUE(
      AnyNote(*asset, "2 line and point statements (l, p) not carried"));
}

TEST(ObjAssetReaderTest, RefusesAUvIndexOutOfRange) {
  EXPECT_THAT(
      ErrorOf(ParseObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n")),
      HasSubstr("m.obj: line 5: texture coordinate index 2 out of range (1 vt "
                "lines)"));
  EXPECT_THAT(
      ErrorOf(ParseObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/-2 2/1 3/1\n")),
      HasSubstr("m.obj: line 5: texture coordinate index -2 out of range (1 so "
                "far)"));
  EXPECT_THAT(
      ErrorOf(ParseObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/0 2/1 3/1\n")),
      HasSubstr("texture coordinate index 0 (OBJ indices start at 1)"));
  EXPECT_THAT(
      ErrorOf(ParseObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n")),
      HasSubstr("m.obj: line 4: vertex index 4 out of range (3 vertices)"));
  EXPECT_THAT(
      ErrorOf(ParseObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2 3/1\n")),
      HasSubstr("face mixes corners with and without texture coordinates"));
}

TEST(ObjAssetReaderTest, RefusesNanCoordinatesAndEmptyMeshes) {
  EXPECT_THAT(
      ErrorOf(ParseObj("v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n")),
      HasSubstr("m.obj: line 2: coordinate \"nan\" is NaN or infinite"));
  EXPECT_THAT(ErrorOf(ParseObj("v 0 0 0\nvt 0 inf\n")),
              HasSubstr("m.obj: line 2: bad texture coordinate \"inf\""));
  // Finite as a double, infinite as the float a UV is (found by fuzzing).
  EXPECT_THAT(ErrorOf(ParseObj("v 0 0 0\nvt 1e300 0\n")),
              HasSubstr("m.obj: line 2: bad texture coordinate \"1e300\""));
  EXPECT_THAT(ErrorOf(ParseObj("v 0 0 0\n")),
              HasSubstr("m.obj: no faces (1 vertices)"));
}

TEST(ObjAssetReaderTest, RefusesMissingSidecarsAndEscapingPaths) {
  const std::string obj =
      "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n";
  const auto no_mtl = ParseObj(obj);
  EXPECT_EQ(no_mtl.status().code(), StatusCode::kNotFound);
  EXPECT_THAT(
      ErrorOf(no_mtl),
      HasSubstr(
          "m.obj: line 1: material library missing: file \"m.mtl\" is not "
          "in the upload"));
  const auto no_texture =
      ParseObj(obj, {{"m.mtl", "newmtl a\nmap_Kd a.png\n"}});
  EXPECT_EQ(no_texture.status().code(), StatusCode::kNotFound);
  EXPECT_THAT(ErrorOf(no_texture),
              HasSubstr("m.obj: texture a.png is missing: file \"a.png\" is "
                        "not in the upload"));
  EXPECT_THAT(
      ErrorOf(
          ParseObj(obj, {{"m.mtl", "newmtl a\nmap_Kd ../../etc/passwd\n"}})),
      HasSubstr(
          "m.mtl: line 2: \"m.mtl\" refers to \"../../etc/passwd\", which "
          "leaves the folder of the upload"));
  EXPECT_THAT(ErrorOf(ParseObj("mtllib /etc/x.mtl\nv 0 0 0\n")),
              HasSubstr("is an absolute path"));
  EXPECT_THAT(
      ErrorOf(ParseObj(obj, {{"m.mtl", "newmtl a\nmap_Kd -zz 1 a.png\n"}})),
      HasSubstr("m.mtl: line 2: map_Kd: unknown option \"-zz\""));
  EXPECT_THAT(ErrorOf(ParseObj(obj, {{"m.mtl", "Kd 1 1 1\n"}})),
              HasSubstr("m.mtl: line 1: Kd before any newmtl"));
  EXPECT_THAT(ErrorOf(ParseObj(obj, {{"m.mtl", "newmtl a\nmap_Kd a.png\n"},
                                     {"a.png", "GIF89a"}})),
              HasSubstr("a.png: image format GIF is not supported"));
}

}  // namespace
}  // namespace meshwave
