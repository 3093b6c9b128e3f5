// The glTF reader on documents built in memory: the scene graph (node
// transforms, mirroring, instancing, cycles), primitives (strips, fans,
// non-indexed, sparse and quantised accessors), attributes, materials and
// their textures, notes, and a message for every malformed input.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "codec/asset/asset_checks_testonly.h"
#include "codec/asset/gltf_builder_testonly.h"
#include "codec/image/png_encoder_testonly.h"
#include "meshwave/file_set.h"
#include "meshwave/mesh_asset.h"

namespace meshwave {
namespace {

using ::testing::ElementsAre;
using testing::GltfBuilder;
using ::testing::HasSubstr;
using testing::OneTriangle;

using testing::AnyNote;
using testing::ErrorOf;
using Files = testing::ExtraFiles;

Result<MeshAsset> Parse(const std::string& main_name, const std::string& bytes,
                        const Files& others = {},
                        const AssetLimits& limits = {}) {
  return testing::ParseInMemory(main_name, bytes, others, limits);
}

Result<MeshAsset> ParseGlb(GltfBuilder& b, const Files& others = {}) {
  return Parse("m.glb", b.Glb(), others);
}

std::string Png2x2() {
  return testing::EncodeRgbaPng(
      2, 2, {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 9, 9, 9, 128});
}

TEST(GltfReaderTest, ReadsATriangleFromGlbAndFromGltfWithItsBin) {
  GltfBuilder b = OneTriangle();
  const auto glb = ParseGlb(b);
  ASSERT_TRUE(glb.ok()) << glb.status().ToString();
  EXPECT_EQ(glb->mesh.positions.size(), 3u);
  EXPECT_THAT(glb->mesh.faces, ElementsAre(Face{0, 1, 2}));
  EXPECT_TRUE(glb->uv.empty());
  EXPECT_TRUE(glb->color.empty());
  EXPECT_TRUE(glb->face_material.empty());
  EXPECT_TRUE(glb->notes.empty());

  const auto gltf = Parse("dir/m.gltf", b.Gltf("data/m%20b.bin"),
                          {{"dir/data/m b.bin", b.bin}});
  ASSERT_TRUE(gltf.ok()) << gltf.status().ToString();
  EXPECT_EQ(gltf->mesh.positions, glb->mesh.positions);
}

TEST(GltfReaderTest, ReadsABufferFromADataUri) {
  GltfBuilder b = OneTriangle();
  static const char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string base64;
  for (size_t i = 0; i < b.bin.size(); i += 3) {
    uint32_t n = static_cast<uint8_t>(b.bin[i]) << 16;
    if (i + 1 < b.bin.size()) n |= static_cast<uint8_t>(b.bin[i + 1]) << 8;
    if (i + 2 < b.bin.size()) n |= static_cast<uint8_t>(b.bin[i + 2]);
    base64 += kAlphabet[(n >> 18) & 63];
    base64 += kAlphabet[(n >> 12) & 63];
    base64 += i + 1 < b.bin.size() ? kAlphabet[(n >> 6) & 63] : '=';
    base64 += i + 2 < b.bin.size() ? kAlphabet[n & 63] : '=';
  }
  const auto asset =
      Parse("m.gltf", b.Gltf("data:application/octet-stream;base64," + base64));
  ASSERT_TRUE(asset.ok()) << asset.status().ToString();
  EXPECT_EQ(asset->mesh.faces.size(), 1u);
}

TEST(GltfReaderTest, AppliesNodeTransformsDownTheTree) {
  GltfBuilder b = OneTriangle();
  b.doc["nodes"][0].erase("mesh");
  // root: scale 2, rotation 90 degrees about z; child: translation (0, 0, 5)
  // then the mesh.
  b.doc["nodes"][0]["scale"] = {2, 2, 2};
  b.doc["nodes"][0]["rotation"] = {0, 0, std::sqrt(0.5), std::sqrt(0.5)};
  b.doc["nodes"][0]["children"] = {1};
  b.Node({{"translation", {0, 0, 5}}, {"mesh", 0}});
  const auto asset = ParseGlb(b);
  ASSERT_TRUE(asset.ok()) << asset.status().ToString();
  // (1, 0, 0) -> (0, 0, 5) + ... : child first, then the root's R * S.
  const Vec3 p1 = asset->mesh.positions[1];
  EXPECT_NEAR(p1.x(), 0.0, 1e-12);
  EXPECT_NEAR(p1.y(), 2.0, 1e-12);
  EXPECT_NEAR(p1.z(), 10.0, 1e-12);
  EXPECT_THAT(asset->mesh.faces, ElementsAre(Face{0, 1, 2}));  // no mirror
}

TEST(GltfReaderTest, AMatrixNodeAndAMirrorFlipTheWinding) {
  GltfBuilder b = OneTriangle();
  // Column-major: x mirrored, translated by (1, 2, 3).
  b.doc["nodes"][0]["matrix"] = {-1, 0, 0, 0, 0, 1, 0, 0,
                                 0,  0, 1, 0, 1, 2, 3, 1};
  const auto asset = ParseGlb(b);
  ASSERT_TRUE(asset.ok()) << asset.status().ToString();
  EXPECT_EQ(asset->mesh.positions[1], Vec3(0, 2, 3));
  EXPECT_THAT(asset->mesh.faces, ElementsAre(Face{0, 2, 1}));
}

TEST(GltfReaderTest, InstancesAMeshPerNodeAndWeldsSharedPositions) {
  GltfBuilder b = OneTriangle();
  b.doc["scenes"][0]["nodes"] = {0, 1, 2};
  b.Node({{"mesh", 0}});  // the same place: welded
  b.Node({{"mesh", 0}, {"translation", {0, 0, 1}}});
  const auto asset = ParseGlb(b);
  ASSERT_TRUE(asset.ok()) << asset.status().ToString();
  EXPECT_EQ(asset->mesh.faces.size(), 3u);
  EXPECT_EQ(asset->mesh.positions.size(), 6u);  // 9 read, 3 merged
  EXPECT_EQ(asset->mesh.faces[0], asset->mesh.faces[1]);
}

TEST(GltfReaderTest, ConvertsStripsFansAndNonIndexedPrimitives) {
  GltfBuilder b;
  const int p = b.Positions({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 2, 0, 0});
  const int strip = b.Indices({0, 1, 2, 3, 4});
  b.Mesh({{{"attributes", {{"POSITION", p}}}, {"indices", strip}, {"mode", 5}},
          {{"attributes", {{"POSITION", p}}}, {"indices", strip}, {"mode", 6}},
          {{"attributes", {{"POSITION", p}}}, {"mode", 4}}});
  b.doc["accessors"][p]["count"] = 5;
  b.Scene({b.Node({{"mesh", 0}})});
  // 5 vertices are not a multiple of 3 for the non-indexed TRIANGLES.
  EXPECT_THAT(ErrorOf(ParseGlb(b)),
              HasSubstr("m.glb: mesh 0 primitive 2: 5 indices for TRIANGLES, "
                        "not a multiple of 3"));
  const int three = b.Positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
  b.doc["meshes"][0]["primitives"][2]["attributes"]["POSITION"] = three;
  const auto asset = ParseGlb(b);
  ASSERT_TRUE(asset.ok()) << asset.status().ToString();
  // Strip: (0 1 2) (1 3 2) (2 3 4) (glTF 2.0's rule); fan: (1 2 0) (2 3 0) (3 4
  // 0); one non-indexed triangle; all welded onto the first five positions.
  ASSERT_EQ(asset->mesh.faces.size(), 7u);
  EXPECT_THAT(std::vector<Face>(asset->mesh.faces.begin(),
                                asset->mesh.faces.begin() + 6),
              ElementsAre(Face{0, 1, 2}, Face{1, 3, 2}, Face{2, 3, 4},
                          Face{1, 2, 0}, Face{2, 3, 0}, Face{3, 4, 0}));
  EXPECT_EQ(asset->mesh.faces[6], (Face{0, 1, 2}));
}

TEST(GltfReaderTest, ReadsSparseAndQuantizedAccessors) {
  GltfBuilder b;
  // SHORT positions (KHR_mesh_quantization), then a sparse override of
  // vertex 2 with (0, 7, 0).
  const int p = b.Data(std::vector<int16_t>{0, 0, 0, 3, 0, 0, 0, 1, 0},
                       testing::kShort, "VEC3", 3);
  const int sparse_index = b.View(std::string("\x02\0", 2));
  std::string value(12, '\0');
  const float seven[3] = {0, 7, 0};
  std::memcpy(value.data(), seven, 12);
  const int sparse_value = b.View(value);
  b.doc["accessors"][p]["sparse"] = {
      {"count", 1},
      {"indices",
       {{"bufferView", sparse_index},
        {"componentType", testing::kUnsignedShort}}},
      {"values", {{"bufferView", sparse_value}}}};
  // Oops: sparse values share the accessor's component type (SHORT).
  const int16_t seven_short[3] = {0, 7, 0};
  std::memcpy(
      b.bin.data() +
          b.doc["bufferViews"][sparse_value]["byteOffset"].get<size_t>(),
      seven_short, 6);
  b.doc["bufferViews"][sparse_value]["byteLength"] = 6;
  b.doc["extensionsUsed"] = {"KHR_mesh_quantization"};
  b.doc["extensionsRequired"] = {"KHR_mesh_quantization"};
  // Normalised UNSIGNED_BYTE texture coordinates.
  const int uv = b.Data(std::vector<uint8_t>{0, 255, 255, 0, 51, 102},
                        testing::kUnsignedByte, "VEC2", 2, true);
  b.Mesh({{{"attributes", {{"POSITION", p}, {"TEXCOORD_0", uv}}}}});
  b.Scene({b.Node({{"mesh", 0}})});
  const auto asset = ParseGlb(b);
  ASSERT_TRUE(asset.ok()) << asset.status().ToString();
  EXPECT_EQ(asset->mesh.positions[1], Vec3(3, 0, 0));
  EXPECT_EQ(asset->mesh.positions[2], Vec3(0, 7, 0));
  EXPECT_FLOAT_EQ(asset->uv.values[0].y(), 1.0f);
  EXPECT_FLOAT_EQ(asset->uv.values[2].x(), 0.2f);
  EXPECT_FLOAT_EQ(asset->uv.values[2].y(), 0.4f);
  EXPECT_TRUE(asset->notes.empty()) << asset->notes[0];
}

TEST(GltfReaderTest, ReadsColoursOfAnyComponentTypeAndFillsDefaults) {
  GltfBuilder b;
  const int p = b.Positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
  const int c8 =
      b.Data(std::vector<uint8_t>{255, 0, 0, 255, 0, 255, 0, 128, 0, 0, 255, 0},
             testing::kUnsignedByte, "VEC4", 4, true);
  const int c16 =
      b.Data(std::vector<uint16_t>{65535, 0, 0, 0, 65535, 0, 0, 0, 65535},
             testing::kUnsignedShort, "VEC3", 3, true);
  const int cf = b.Data(std::vector<float>{0.5f, 2.0f, -1.0f, 0, 0, 0, 1, 1, 1},
                        testing::kFloat, "VEC3", 3);
  b.Mesh({{{"attributes", {{"POSITION", p}, {"COLOR_0", c8}}}},
          {{"attributes", {{"POSITION", p}, {"COLOR_0", c16}}}},
          {{"attributes", {{"POSITION", p}, {"COLOR_0", cf}}}},
          {{"attributes", {{"POSITION", p}}}}});
  b.Scene({b.Node({{"mesh", 0}})});
  const auto asset = ParseGlb(b);
  ASSERT_TRUE(asset.ok()) << asset.status().ToString();
  ASSERT_EQ(asset->color.values.size(), 10u);  // 3 x 3 + the shared white
  EXPECT_EQ(asset->color.values[1], Eigen::Vector4f(0, 1, 0, 128.0f / 255));
  EXPECT_EQ(asset->color.values[3], Eigen::Vector4f(1, 0, 0, 1));
  EXPECT_EQ(asset->color.values[6], Eigen::Vector4f(0.5f, 1, 0, 1));  // clamped
  EXPECT_EQ(asset->color.faces[3], (Face{9, 9, 9}));
  EXPECT_EQ(asset->color.values[9], Eigen::Vector4f(1, 1, 1, 1));
  EXPECT_TRUE(AnyNote(*asset, "COLOR_0 values outside [0, 1] clamped"));
}

TEST(GltfReaderTest, ConvertsMaterialsTexturesAndTheirTransforms) {
  GltfBuilder b = OneTriangle();
  const int uv = b.Uvs({0, 0, 1, 0, 0, 1});
  b.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = uv;
  b.doc["meshes"][0]["primitives"][0]["material"] = 0;
  b.doc["meshes"][0]["primitives"].push_back(
      b.doc["meshes"][0]["primitives"][0]);
  b.doc["meshes"][0]["primitives"][1].erase("material");  // the default one
  const int image_view = b.View(Png2x2());
  b.doc["images"] = {{{"bufferView", image_view}, {"mimeType", "image/png"}},
                     {{"uri", "tex/other.png"}}};
  b.doc["samplers"] = {{{"wrapS", 33071}, {"wrapT", 33648}}};
  b.doc["textures"] = {{{"source", 0}, {"sampler", 0}}, {{"source", 1}}};
  b.doc["materials"] = {
      {{"name", "painted"},
       {"pbrMetallicRoughness",
        {{"baseColorFactor", {0.5, 0.25, 1, 1}},
         {"baseColorTexture",
          {{"index", 0},
           {"extensions",
            {{"KHR_texture_transform",
              {{"offset", {0.5, 0.25}},
               {"scale", {2, 3}},
               {"rotation", M_PI / 2}}}}}}},
         {"metallicFactor", 0.25},
         {"roughnessFactor", 0.75},
         {"metallicRoughnessTexture", {{"index", 1}}}}},
       {"normalTexture", {{"index", 1}, {"scale", 0.5}}},
       {"occlusionTexture", {{"index", 1}, {"strength", 0.3}, {"texCoord", 1}}},
       {"emissiveFactor", {1, 0.5, 0}},
       {"alphaMode", "MASK"},
       {"alphaCutoff", 0.4},
       {"doubleSided", true}}};
  b.doc["extensionsUsed"] = {"KHR_texture_transform"};
  const auto asset = ParseGlb(b, {{"tex/other.png", Png2x2()}});
  ASSERT_TRUE(asset.ok()) << asset.status().ToString();
  ASSERT_EQ(asset->materials.size(), 2u);
  EXPECT_THAT(asset->face_material, ElementsAre(0u, 1u));
  const Material& m = asset->materials[0];
  EXPECT_EQ(m.name, "painted");
  EXPECT_EQ(m.base_color_factor, Eigen::Vector4f(0.5f, 0.25f, 1, 1));
  EXPECT_EQ(m.base_color_texture.image, 0);
  EXPECT_EQ(m.base_color_texture.wrap_u, WrapMode::kClampToEdge);
  EXPECT_EQ(m.base_color_texture.wrap_v, WrapMode::kMirroredRepeat);
  // T * R * S with a quarter turn: u' = 3 v + 0.5, v' = -2 u + 0.25.
  Eigen::Matrix<float, 2, 3> expected;
  expected << 0, 3, 0.5f, -2, 0, 0.25f;
  EXPECT_TRUE(m.base_color_texture.transform.isApprox(expected, 1e-6f))
      << m.base_color_texture.transform;
  EXPECT_EQ(m.metallic_roughness_texture.image, 1);
  EXPECT_EQ(m.metallic_roughness_texture.wrap_u, WrapMode::kRepeat);
  EXPECT_FLOAT_EQ(m.metallic_factor, 0.25f);
  EXPECT_FLOAT_EQ(m.roughness_factor, 0.75f);
  EXPECT_EQ(m.normal_texture.image, 1);
  EXPECT_FLOAT_EQ(m.normal_scale, 0.5f);
  EXPECT_FALSE(m.occlusion_texture.present());  // reads TEXCOORD_1
  EXPECT_TRUE(AnyNote(
      *asset, "occlusionTexture reads TEXCOORD_1, which is not carried"));
  EXPECT_EQ(m.emissive_factor, Eigen::Vector3f(1, 0.5f, 0));
  EXPECT_EQ(m.alpha_mode, AlphaMode::kMask);
  EXPECT_FLOAT_EQ(m.alpha_cutoff, 0.4f);
  EXPECT_TRUE(m.double_sided);
  EXPECT_EQ(asset->materials[1].name, "default");
  ASSERT_EQ(asset->images.size(), 2u);
  EXPECT_EQ(asset->images[0].mime_type, "image/png");
  EXPECT_EQ(asset->images[0].encoded, Png2x2());
  EXPECT_EQ(asset->images[0].width, 2u);
  EXPECT_EQ(asset->images[0].rgba[15], 128);
  EXPECT_EQ(asset->images[1].name, "tex/other.png");
}

TEST(GltfReaderTest, RefusesMaterialFactorsBeyondFloatRange) {
  GltfBuilder b = OneTriangle();
  b.doc["materials"] = {
      {{"pbrMetallicRoughness", {{"baseColorFactor", {1e300, 1, 1, 1}}}}}};
  EXPECT_THAT(ErrorOf(ParseGlb(b)),
              HasSubstr("m.glb: material 0: baseColorFactor needs 4 finite numbers"));
}

TEST(GltfReaderTest, NotesWhatItDoesNotCarry) {
  GltfBuilder b = OneTriangle();
  auto& prim = b.doc["meshes"][0]["primitives"][0];
  const int p = prim["attributes"]["POSITION"];
  prim["attributes"]["NORMAL"] = p;
  prim["attributes"]["TEXCOORD_1"] = b.Uvs({0, 0, 1, 0, 0, 1});
  prim["targets"] = {{{"POSITION", p}}};
  b.doc["meshes"][0]["primitives"].push_back(
      {{"attributes", {{"POSITION", p}}}, {"mode", 0}});
  b.doc["extensionsUsed"] = {"KHR_materials_clearcoat", "KHR_lights_punctual",
                             "VENDOR_thing"};
  b.doc["cameras"] = {{{"type", "perspective"},
                       {"perspective", {{"yfov", 1}, {"znear", 0.1}}}}};
  b.doc["animations"] = nlohmann::json::array();
  b.Mesh({{{"attributes", {{"POSITION", p}}}}});  // drawn by no node
  const auto asset = ParseGlb(b);
  ASSERT_TRUE(asset.ok()) << asset.status().ToString();
  EXPECT_TRUE(AnyNote(
      *asset,
      "m.glb: KHR_materials_clearcoat not carried: the clearcoat layer"));
  EXPECT_TRUE(AnyNote(*asset, "KHR_lights_punctual not carried: lights"));
  EXPECT_TRUE(AnyNote(*asset, "VENDOR_thing not carried"));
  EXPECT_TRUE(AnyNote(*asset, "1 camera not carried"));
  EXPECT_TRUE(
      AnyNote(*asset, "NORMAL not carried (recomputed from the surface)"));
  EXPECT_TRUE(AnyNote(*asset, "vertex attributes TEXCOORD_1 not carried"));
  EXPECT_TRUE(AnyNote(*asset, "morph targets of 1 primitive(s) not carried"));
  EXPECT_TRUE(AnyNote(*asset, "1 point or line primitive(s) not carried"));
  EXPECT_TRUE(AnyNote(*asset, "1 mesh not drawn by any node of the scene"));
}

// ---- refusals: each with its message, and no asset ----

TEST(GltfReaderTest, RefusesATruncatedGlb) {
  GltfBuilder b = OneTriangle();
  const std::string glb = b.Glb();
  EXPECT_THAT(ErrorOf(Parse("m.glb", glb.substr(0, glb.size() - 8))),
              HasSubstr("m.glb: truncated: the GLB header declares"));
  EXPECT_THAT(ErrorOf(Parse("m.glb", glb.substr(0, 10))),
              HasSubstr("m.glb: GLB header truncated"));
  GltfBuilder d = OneTriangle();
  d.doc["accessors"][0]["count"] = 300;  // positions past the end of their view
  EXPECT_THAT(
      ErrorOf(ParseGlb(d)),
      HasSubstr("m.glb: mesh 0 primitive 0: POSITION (accessor 0) reaches past "
                "the end of bufferView 0"));
}

TEST(GltfReaderTest, RefusesATruncatedBin) {
  GltfBuilder b = OneTriangle();
  const std::string size = std::to_string(b.bin.size());
  const auto asset =
      Parse("m.gltf", b.Gltf("m.bin"), {{"m.bin", b.bin.substr(0, 20)}});
  EXPECT_EQ(asset.status().code(), StatusCode::kParseError);
  EXPECT_THAT(ErrorOf(asset),
              HasSubstr("m.gltf: buffer 0 (m.bin) declares " + size +
                        " bytes, the file has 20: truncated"));
  // The GLB's BIN chunk shorter than buffer 0 says.
  nlohmann::json doc = b.doc;
  doc["buffers"] = {{{"byteLength", b.bin.size()}}};
  EXPECT_THAT(ErrorOf(Parse(
                  "m.glb", GltfBuilder::AssembleGlb(doc, b.bin.substr(0, 24)))),
              HasSubstr("m.glb: truncated: buffer 0 declares " + size +
                        " bytes, the GLB's BIN chunk holds 24"));
}

TEST(GltfReaderTest, RefusesAMissingBinAndAMissingImage) {
  GltfBuilder b = OneTriangle();
  const auto no_bin = Parse("m.gltf", b.Gltf("m.bin"));
  EXPECT_EQ(no_bin.status().code(), StatusCode::kNotFound);
  EXPECT_THAT(
      ErrorOf(no_bin),
      HasSubstr("m.gltf: buffer 0: file \"m.bin\" is not in the upload"));
  b.doc["images"] = {{{"uri", "wood.png"}}};
  const auto no_image = Parse("m.gltf", b.Gltf("m.bin"), {{"m.bin", b.bin}});
  EXPECT_EQ(no_image.status().code(), StatusCode::kNotFound);
  EXPECT_THAT(ErrorOf(no_image),
              HasSubstr("m.gltf: image 0 is missing: file \"wood.png\" is not "
                        "in the upload"));
}

TEST(GltfReaderTest, RefusesPathsThatLeaveTheFileSet) {
  GltfBuilder b = OneTriangle();
  for (const char* uri :
       {"../../m.bin", "/etc/passwd", "file:///etc/passwd",
        "http://example.com/m.bin", "a\\..\\..\\m.bin", "%2e%2e/%2e%2e/m.bin"}) {
    const auto asset = Parse("d/m.gltf", b.Gltf(uri), {{"m.bin", b.bin}});
    EXPECT_EQ(asset.status().code(), StatusCode::kInvalidArgument) << uri;
    EXPECT_THAT(ErrorOf(asset), HasSubstr("\"d/m.gltf\" refers to")) << uri;
  }
  b.doc["images"] = {{{"uri", "../../secret.png"}}};
  EXPECT_THAT(ErrorOf(Parse("d/m.gltf", b.Gltf("m.bin"), {{"d/m.bin", b.bin}})),
              HasSubstr("leaves the folder of the upload"));
}

TEST(GltfReaderTest, RefusesIndicesOutOfRangeAndNaNPositions) {
  GltfBuilder b = OneTriangle();
  b.Indices({0, 1, 3});
  b.doc["meshes"][0]["primitives"][0]["indices"] = 2;
  EXPECT_THAT(
      ErrorOf(ParseGlb(b)),
      HasSubstr(
          "m.glb: mesh 0 primitive 0: index 3 out of range (3 vertices)"));
  GltfBuilder n;
  const int p = n.Positions({0, 0, 0, NAN, 0, 0, 0, 1, 0});
  n.Mesh({{{"attributes", {{"POSITION", p}}}}});
  n.Scene({n.Node({{"mesh", 0}})});
  EXPECT_THAT(ErrorOf(ParseGlb(n)),
              HasSubstr("m.glb: mesh 0 primitive 0: POSITION of vertex 1 is "
                        "NaN or infinite"));
  GltfBuilder u = OneTriangle();
  u.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] =
      u.Uvs({0, 0, 1, INFINITY, 0, 1});
  EXPECT_THAT(ErrorOf(ParseGlb(u)),
              HasSubstr("TEXCOORD_0 of vertex 1 is NaN or infinite"));
}

TEST(GltfReaderTest, RefusesNodeCyclesAndSharedChildren) {
  GltfBuilder b = OneTriangle();
  b.doc["nodes"][0]["children"] = {1};
  b.Node({{"children", {0}}});  // 0 -> 1 -> 0
  EXPECT_THAT(
      ErrorOf(ParseGlb(b)),
      HasSubstr("m.glb: node 0 is reached twice from the scene: a cycle "
                "in the node tree"));
  GltfBuilder c = OneTriangle();
  c.doc["nodes"][0]["children"] = {1};
  c.Node({{"children", {1}}});  // its own child, and node 0's
  EXPECT_THAT(ErrorOf(ParseGlb(c)),
              HasSubstr("m.glb: node 1 has two parents (nodes 0 and 1); glTF "
                        "nodes form trees"));
  GltfBuilder deep = OneTriangle();
  for (int i = 0; i < 70; ++i) {
    deep.doc["nodes"][i]["children"] = {i + 1};
    deep.Node(nlohmann::json::object());
  }
  EXPECT_THAT(ErrorOf(ParseGlb(deep)),
              HasSubstr("the node tree is deeper than 64 levels"));
}

TEST(GltfReaderTest, RefusesCompressedGeometryItCannotDecode) {
  GltfBuilder b = OneTriangle();
  b.doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  b.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  const auto draco = ParseGlb(b);
  EXPECT_EQ(draco.status().code(), StatusCode::kUnsupported);
  EXPECT_THAT(
      ErrorOf(draco),
      HasSubstr("m.glb: the geometry is compressed with "
                "KHR_draco_mesh_compression, which meshwave does not decode"));
  b.doc["extensionsRequired"] = {"EXT_meshopt_compression"};
  EXPECT_THAT(ErrorOf(ParseGlb(b)), HasSubstr("EXT_meshopt_compression"));
  // Used but not required: the uncompressed fallback is read, and noted.
  b.doc.erase("extensionsRequired");
  const auto fallback = ParseGlb(b);
  ASSERT_TRUE(fallback.ok()) << fallback.status().ToString();
  EXPECT_TRUE(AnyNote(*fallback, "KHR_draco_mesh_compression not carried"));
}

TEST(GltfReaderTest, RefusesWhatWouldHurtTinygltf) {
  // Deep nesting (tinygltf converts extras recursively).
  GltfBuilder b = OneTriangle();
  std::string deep = "1";
  for (int i = 0; i < 100; ++i) deep = "[" + deep + "]";
  std::string json = b.Gltf("m.bin");
  json.insert(1, "\"extras\":" + deep + ",");
  EXPECT_THAT(ErrorOf(Parse("m.gltf", json, {{"m.bin", b.bin}})),
              HasSubstr("m.gltf: the glTF JSON nests deeper than 64 levels"));
  // Many small values (each costs far more parsed than written).
  AssetLimits few;
  few.max_json_values = 30;
  EXPECT_THAT(
      ErrorOf(Parse("m.gltf", b.Gltf("m.bin"), {{"m.bin", b.bin}}, few)),
      HasSubstr("m.gltf: the glTF JSON holds more than 30 values"));
  // In a .glb, buffers other than 0 may not stand for the BIN chunk
  // (tinygltf would copy the chunk once for each).
  GltfBuilder many = OneTriangle();
  nlohmann::json two = many.doc;
  two["buffers"] = {{{"byteLength", many.bin.size()}},
                    {{"byteLength", many.bin.size()}}};
  EXPECT_THAT(
      ErrorOf(Parse("m.glb", GltfBuilder::AssembleGlb(two, many.bin))),
      HasSubstr("m.glb: buffer 1 has no uri; in a .glb only buffer 0 may "
                "stand for the BIN chunk"));
  // An image's bufferView past the end of its buffer (tinygltf reads it
  // unchecked).
  GltfBuilder img = OneTriangle();
  const int view = img.View(Png2x2());
  img.doc["bufferViews"][view]["byteLength"] = 100000;
  img.doc["images"] = {{{"bufferView", view}, {"mimeType", "image/png"}}};
  EXPECT_THAT(ErrorOf(ParseGlb(img)),
              HasSubstr("m.glb: bufferView 2 spans bytes"));
  // Not JSON, not glTF 2.0.
  EXPECT_THAT(ErrorOf(Parse("m.gltf", "{\"asset\":")),
              HasSubstr("m.gltf: invalid JSON at byte"));
  EXPECT_THAT(ErrorOf(Parse("m.gltf", "{\"asset\":{\"version\":\"1.0\"}}")),
              HasSubstr("glTF version \"1.0\" (only glTF 2.0 is supported)"));
}

TEST(GltfReaderTest, ImagesAreDecodedWithLimits) {
  GltfBuilder b = OneTriangle();
  const int view = b.View(testing::BombPng(20000, 20000));
  b.doc["images"] = {{{"bufferView", view}, {"mimeType", "image/png"}}};
  b.doc["textures"] = {{{"source", 0}}};
  b.doc["materials"] = {
      {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
  b.doc["meshes"][0]["primitives"][0]["material"] = 0;
  const auto asset = ParseGlb(b);
  EXPECT_EQ(asset.status().code(), StatusCode::kUnsupported);
  EXPECT_THAT(ErrorOf(asset),
              HasSubstr("m.glb image 0: PNG declares 20000x20000"));
  // Unused by any carried slot, the same image is kept undecoded, noted.
  b.doc["materials"][0]["pbrMetallicRoughness"].erase("baseColorTexture");
  const auto kept = ParseGlb(b);
  ASSERT_TRUE(kept.ok()) << kept.status().ToString();
  EXPECT_TRUE(kept->images[0].rgba.empty());
  EXPECT_TRUE(AnyNote(*kept, "kept undecoded"));
}

}  // namespace
}  // namespace meshwave
