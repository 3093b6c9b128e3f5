// The glTF 2.0 writer (SerializeGltf, WriteMesh to .glb/.gltf): the GLB
// container's header and chunks, the JSON's structure (one scene, node,
// mesh; FLOAT VEC3 positions with min/max, UNSIGNED_INT indices), the
// buffer's bytes, and the .gltf form's base64 buffer equal to the GLB's.
// tests/gltf validates whole files with the Khronos glTF-Validator.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "codec/mesh/mesh_builders_testonly.h"
#include "meshwave/gltf.h"
#include "meshwave/mesh.h"
#include "meshwave/mesh_io.h"

namespace meshwave {
namespace {

using ::testing::EndsWith;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::StartsWith;

uint32_t U32(const std::string& s, size_t at) {
  uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = v << 8 | static_cast<uint8_t>(s.at(at + i));
  return v;
}

float F32(const std::string& s, size_t at) {
  const uint32_t bits = U32(s, at);
  float f;
  std::memcpy(&f, &bits, 4);
  return f;
}

struct Glb {
  std::string json, bin;
};

// Splits a GLB, checking its header and chunk framing on the way.
Glb SplitGlb(const std::string& glb) {
  Glb out;
  EXPECT_EQ(U32(glb, 0), 0x46546C67u);  // "glTF"
  EXPECT_EQ(U32(glb, 4), 2u);
  EXPECT_EQ(U32(glb, 8), glb.size());
  const uint32_t json_length = U32(glb, 12);
  EXPECT_EQ(json_length % 4, 0u);
  EXPECT_EQ(glb.substr(16, 4), "JSON");
  out.json = glb.substr(20, json_length);
  size_t at = 20 + json_length;
  if (at < glb.size()) {
    const uint32_t bin_length = U32(glb, at);
    EXPECT_EQ(bin_length % 4, 0u);
    EXPECT_EQ(glb.substr(at + 4, 4), std::string("BIN\0", 4));
    out.bin = glb.substr(at + 8, bin_length);
    EXPECT_EQ(at + 8 + bin_length, glb.size());
  }
  return out;
}

std::string Base64Decode(const std::string& text) {
  const std::string digits =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  uint32_t acc = 0;
  int bits = 0;
  for (char c : text) {
    if (c == '=') break;
    const size_t d = digits.find(c);
    EXPECT_NE(d, std::string::npos) << "not base64: " << c;
    acc = acc << 6 | static_cast<uint32_t>(d);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out += static_cast<char>((acc >> bits) & 0xff);
    }
  }
  return out;
}

TEST(GltfWriterTest, GlbHoldsOneIndexedTrianglePrimitive) {
  TriMesh mesh = testing::Tetrahedron();
  mesh.positions[3] = Vec3(-0.5, 2.25, 1e-3);
  const Glb glb = SplitGlb(SerializeGltf(mesh, GltfForm::kBinary));
  EXPECT_THAT(
      glb.json,
      StartsWith(R"({"asset":{"version":"2.0","generator":"meshwave"})"));
  EXPECT_THAT(
      glb.json,
      HasSubstr(R"("scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}])"));
  EXPECT_THAT(
      glb.json,
      HasSubstr(
          R"("primitives":[{"attributes":{"POSITION":0},"indices":1,"mode":4}])"));
  // Positions: FLOAT (5126) VEC3 with the data's bounds; indices:
  // UNSIGNED_INT (5125) SCALAR, three per face.
  EXPECT_THAT(
      glb.json,
      HasSubstr(
          R"({"bufferView":0,"componentType":5126,"count":4,)"
          R"("type":"VEC3","min":[-0.5,0,0],"max":[1,2.25,0.0010000000474974513]})"));
  EXPECT_THAT(
      glb.json,
      HasSubstr(
          R"({"bufferView":1,"componentType":5125,"count":12,"type":"SCALAR"})"));
  EXPECT_THAT(glb.json, HasSubstr(R"("buffers":[{"byteLength":96}])"));
  EXPECT_THAT(glb.json, Not(HasSubstr("uri")));
  // Space padding after the JSON, nothing else.
  EXPECT_THAT(glb.json.substr(0, glb.json.find_last_not_of(' ') + 1),
              EndsWith("}"));

  ASSERT_EQ(glb.bin.size(), 4 * 12 + 4 * 12u);
  for (size_t v = 0; v < 4; ++v) {
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(F32(glb.bin, v * 12 + a * 4),
                static_cast<float>(mesh.positions[v][a]));
    }
  }
  for (size_t f = 0; f < 4; ++f) {
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(U32(glb.bin, 48 + f * 12 + c * 4), mesh.faces[f][c]);
  }
}

TEST(GltfWriterTest, GltfEmbedsTheGlbBufferAsBase64) {
  const TriMesh mesh = testing::Grid(3);  // 16 vertices: base64 padding too
  const Glb glb = SplitGlb(SerializeGltf(mesh, GltfForm::kBinary));
  const std::string gltf = SerializeGltf(mesh, GltfForm::kEmbedded);
  const std::string prefix = R"("uri":"data:application/octet-stream;base64,)";
  const size_t at = gltf.find(prefix);
  ASSERT_NE(at, std::string::npos) << gltf;
  const size_t start = at + prefix.size();
  const std::string encoded = gltf.substr(start, gltf.find('"', start) - start);
  EXPECT_EQ(encoded.size() % 4, 0u);
  EXPECT_EQ(Base64Decode(encoded), glb.bin);
  // The same JSON otherwise.
  std::string without = gltf;
  without.erase(at - 1, prefix.size() + encoded.size() + 2);
  EXPECT_EQ(without,
            glb.json.substr(0, glb.json.find_last_not_of(' ') + 1) + "\n");
}

TEST(GltfWriterTest, TexturedGlbSplitsVerticesByUvAndEmbedsTheImages) {
  TriMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  mesh.faces = {{0, 1, 2}, {0, 2, 3}};
  // Vertex 0 has one UV in both faces, vertex 2 two (a cut between them).
  const std::vector<float> uvs = {0.1f, 0.1f, 0.9f, 0.1f, 0.9f, 0.9f,
                                  0.1f, 0.1f, 0.5f, 0.5f, 0.1f, 0.9f};
  const std::string png("\x89PNG\r\n\x1a\nnot really", 18);
  std::vector<TextureImage> images(2);
  images[0].role = TextureRole::kBaseColor;
  images[0].mime_type = "image/png";
  images[0].bytes = png;
  images[1].role = TextureRole::kNormal;
  images[1].mime_type = "image/jpeg";
  images[1].bytes = "\xff\xd8jpeg";
  TextureMaterial material;
  material.normal_scale = 0.5f;
  material.alpha_blend = true;
  EXPECT_EQ(TexturedVertexCount(mesh, uvs), 5u);
  const std::string bytes = SerializeTexturedGltf(mesh, GltfForm::kBinary, uvs, images, material);
  const Glb glb = SplitGlb(bytes);
  EXPECT_THAT(glb.json, HasSubstr(R"("attributes":{"POSITION":0,"TEXCOORD_0":2,"NORMAL":3,"TANGENT":4},"indices":1,"material":0)"));
  EXPECT_THAT(glb.json, HasSubstr(R"({"bufferView":0,"componentType":5126,"count":5,)"));
  EXPECT_THAT(glb.json, HasSubstr(R"({"bufferView":2,"componentType":5126,"count":5,"type":"VEC2"})"));
  EXPECT_THAT(glb.json, HasSubstr(R"("baseColorTexture":{"index":0})"));
  EXPECT_THAT(glb.json, HasSubstr(R"("normalTexture":{"index":1,"scale":0.5})"));
  EXPECT_THAT(glb.json, HasSubstr(R"("alphaMode":"BLEND")"));
  EXPECT_THAT(glb.json, HasSubstr(R"("samplers":[{"magFilter":9729,"minFilter":9987,"wrapS":33071,"wrapT":33071}])"));
  EXPECT_THAT(glb.json, HasSubstr(R"("images":[{"bufferView":5,"mimeType":"image/png"},{"bufferView":6,"mimeType":"image/jpeg"}])"));
  // Positions 5 x 12 bytes, indices 6 x 4, UVs 5 x 8, normals 5 x 12 and
  // tangents 5 x 16 (a normal map needs them), then the images at
  // 4-aligned offsets.
  EXPECT_EQ(glb.bin.substr(264, png.size()), png);
  EXPECT_THAT(glb.json, HasSubstr(R"({"buffer":0,"byteOffset":264,"byteLength":18})"));
  EXPECT_EQ(glb.bin.substr(284, 6), images[1].bytes);
  // The square lies in z = 0: normal +z everywhere, right-handed; face 0
  // maps u along x, so its own vertices (written 1 and 2) have tangent +x.
  for (size_t v = 0; v < 5; ++v) {
    EXPECT_EQ(F32(glb.bin, 124 + 12 * v + 8), 1.0f) << v;
    EXPECT_EQ(F32(glb.bin, 184 + 16 * v + 12), 1.0f) << v;
  }
  for (size_t v : {1, 2}) EXPECT_NEAR(F32(glb.bin, 184 + 16 * v), 1.0f, 1e-6) << v;
  // Corner UVs as written: face 1's corner 1 (vertex 2) got a vertex of its
  // own, the fourth written, at vertex 2's position.
  EXPECT_EQ(U32(glb.bin, 60 + 16), 3u);
  EXPECT_EQ(F32(glb.bin, 84 + 3 * 8), 0.5f);
  EXPECT_EQ(F32(glb.bin, 3 * 12), 1.0f);
  EXPECT_EQ(F32(glb.bin, 3 * 12 + 4), 1.0f);
  // The geometry reads back (the reader welds the split vertex again).
  const auto dir = std::filesystem::temp_directory_path() /
                   ("meshwave_gltf_textured_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  { std::ofstream(dir / "t.glb", std::ios::binary) << bytes; }
  const Result<TriMesh> back = ReadMesh(dir / "t.glb");
  std::filesystem::remove_all(dir);
  ASSERT_TRUE(back.ok()) << back.status().ToString();
  EXPECT_EQ(back->positions.size(), 4u);
  EXPECT_EQ(back->faces, mesh.faces);
  // Without images: the untextured file.
  EXPECT_EQ(SerializeTexturedGltf(mesh, GltfForm::kBinary, uvs, {}, material),
            SerializeGltf(mesh, GltfForm::kBinary));
  EXPECT_THAT(glb.json, Not(HasSubstr("EXT_texture_webp")));
}

// A WebP image is what glTF 2.0's core does not know: its texture names it
// through EXT_texture_webp, which the file uses and requires.
TEST(GltfWriterTest, AWebpTextureGoesThroughExtTextureWebp) {
  TriMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
  mesh.faces = {{0, 1, 2}};
  const std::vector<float> uvs = {0, 0, 1, 0, 1, 1};
  std::vector<TextureImage> images(2);
  images[0].role = TextureRole::kBaseColor;
  images[0].mime_type = "image/webp";
  images[0].bytes = "RIFF....WEBPVP8 ";
  images[1].role = TextureRole::kMetallicRoughness;
  images[1].mime_type = "image/jpeg";
  images[1].bytes = "\xff\xd8jpeg";
  const Glb glb =
      SplitGlb(SerializeTexturedGltf(mesh, GltfForm::kBinary, uvs, images, TextureMaterial{}));
  EXPECT_THAT(glb.json, HasSubstr(R"("extensionsUsed":["EXT_texture_webp"],"extensionsRequired":["EXT_texture_webp"])"));
  EXPECT_THAT(glb.json, HasSubstr(R"("textures":[{"sampler":0,"extensions":{"EXT_texture_webp":{"source":0}}},{"sampler":0,"source":1}])"));
  EXPECT_THAT(glb.json, HasSubstr(R"("mimeType":"image/webp")"));
}

TEST(GltfWriterTest, AMeshWithoutFacesIsAnEmptyScene) {
  TriMesh mesh;
  const std::string glb = SerializeGltf(mesh, GltfForm::kBinary);
  const Glb parts = SplitGlb(glb);
  EXPECT_THAT(parts.json, HasSubstr(R"("scenes":[{"nodes":[]}]})"));
  EXPECT_TRUE(parts.bin.empty());
  EXPECT_THAT(parts.json, Not(HasSubstr("buffers")));
}

TEST(GltfWriterTest, WriteMeshChoosesGltfByExtension) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("meshwave_gltf_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const TriMesh mesh = testing::Tetrahedron();
  for (const auto& [name, form] : {std::pair{"t.glb", GltfForm::kBinary},
                                   std::pair{"t.GLTF", GltfForm::kEmbedded}}) {
    ASSERT_TRUE(WriteMesh(mesh, dir / name).ok()) << name;
    std::ifstream in(dir / name, std::ios::binary);
    std::stringstream bytes;
    bytes << in.rdbuf();
    EXPECT_EQ(bytes.str(), SerializeGltf(mesh, form)) << name;
  }
  EXPECT_EQ(GltfFormFromPath("a/b.GlB"), GltfForm::kBinary);
  EXPECT_EQ(GltfFormFromPath("b.ply"), std::nullopt);
  // Both forms read back (ReadMesh reads glTF geometry): the same
  // positions, bit for bit, and faces.
  for (const char* name : {"t.glb", "t.GLTF"}) {
    const Result<TriMesh> back = ReadMesh(dir / name);
    ASSERT_TRUE(back.ok()) << name << ": " << back.status().ToString();
    EXPECT_EQ(back->positions, mesh.positions) << name;
    EXPECT_EQ(back->faces, mesh.faces) << name;
  }
  const Result<TriMesh> stl = ReadMesh(dir / "t.stl");
  EXPECT_EQ(stl.status().code(), StatusCode::kInvalidArgument);
  EXPECT_THAT(stl.status().message(),
              HasSubstr("expected .ply, .obj, .off, .glb or .gltf"));
  const Status unknown = WriteMesh(mesh, dir / "t.stl");
  EXPECT_EQ(unknown.code(), StatusCode::kInvalidArgument);
  EXPECT_THAT(unknown.message(), HasSubstr("write .ply, .obj, .glb or .gltf"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace meshwave
