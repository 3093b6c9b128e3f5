// Builds small glTF documents for the reader tests: a JSON document
// (nlohmann-json, which tests may edit freely to break it) and a binary
// buffer, written out as a .glb or as a .gltf with its .bin.
#ifndef MESHWAVE_TESTS_CODEC_ASSET_GLTF_BUILDER_TESTONLY_H_
#define MESHWAVE_TESTS_CODEC_ASSET_GLTF_BUILDER_TESTONLY_H_

#include <nlohmann/json.hpp>

#include <array>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace meshwave::testing {

inline constexpr int kByte = 5120;
inline constexpr int kUnsignedByte = 5121;
inline constexpr int kShort = 5122;
inline constexpr int kUnsignedShort = 5123;
inline constexpr int kUnsignedInt = 5125;
inline constexpr int kFloat = 5126;

class GltfBuilder {
 public:
  GltfBuilder() {
    doc["asset"] = {{"version", "2.0"}};
    doc["bufferViews"] = nlohmann::json::array();
    doc["accessors"] = nlohmann::json::array();
  }

  // Appends bytes (4-aligned) as a bufferView; returns its index.
  int View(const std::string& bytes, int stride = 0) {
    while (bin.size() % 4 != 0) bin += '\0';
    nlohmann::json view = {{"buffer", 0},
                           {"byteOffset", bin.size()},
                           {"byteLength", bytes.size()}};
    if (stride != 0) view["byteStride"] = stride;
    bin += bytes;
    doc["bufferViews"].push_back(view);
    return static_cast<int>(doc["bufferViews"].size()) - 1;
  }

  int Accessor(int view, int component_type, size_t count,
               const std::string& type, bool normalized = false) {
    nlohmann::json a = {
        {"componentType", component_type}, {"count", count}, {"type", type}};
    if (view >= 0) a["bufferView"] = view;
    if (normalized) a["normalized"] = true;
    doc["accessors"].push_back(a);
    return static_cast<int>(doc["accessors"].size()) - 1;
  }

  // Packs `values` as T and adds a view and an accessor for them.
  template <class T>
  int Data(const std::vector<T>& values, int component_type,
           const std::string& type, int components, bool normalized = false) {
    std::string bytes(values.size() * sizeof(T), '\0');
    std::memcpy(bytes.data(), values.data(), bytes.size());
    return Accessor(View(bytes), component_type, values.size() / components,
                    type, normalized);
  }
  int Positions(const std::vector<float>& xyz) {
    return Data(xyz, kFloat, "VEC3", 3);
  }
  int Indices(const std::vector<uint16_t>& indices) {
    return Data(indices, kUnsignedShort, "SCALAR", 1);
  }
  int Uvs(const std::vector<float>& uv) { return Data(uv, kFloat, "VEC2", 2); }

  int Mesh(const nlohmann::json& primitives) {
    doc["meshes"].push_back({{"primitives", primitives}});
    return static_cast<int>(doc["meshes"].size()) - 1;
  }
  int Node(const nlohmann::json& node) {
    doc["nodes"].push_back(node);
    return static_cast<int>(doc["nodes"].size()) - 1;
  }
  void Scene(const std::vector<int>& roots) {
    doc["scenes"] = {{{"nodes", roots}}};
    doc["scene"] = 0;
  }

  // A .glb: buffer 0 is the BIN chunk.
  std::string Glb() const {
    nlohmann::json d = doc;
    if (!bin.empty()) d["buffers"] = {{{"byteLength", bin.size()}}};
    return AssembleGlb(d, bin);
  }

  // A .glb of `json` and a BIN chunk of `chunk` (padded to 4 bytes; none
  // when empty), whatever the JSON's buffers say.
  static std::string AssembleGlb(const nlohmann::json& json,
                                 std::string chunk) {
    std::string text = json.dump();
    while (text.size() % 4 != 0) text += ' ';
    while (chunk.size() % 4 != 0) chunk += '\0';
    std::string out = "glTF";
    Put32(out, 2);
    Put32(out, static_cast<uint32_t>(12 + 8 + text.size() +
                                     (chunk.empty() ? 0 : 8 + chunk.size())));
    Put32(out, static_cast<uint32_t>(text.size()));
    out += "JSON" + text;
    if (!chunk.empty()) {
      Put32(out, static_cast<uint32_t>(chunk.size()));
      out += std::string("BIN\0", 4) + chunk;
    }
    return out;
  }

  // A .gltf whose buffer 0 is the file `bin_uri` (holding `bin`).
  std::string Gltf(const std::string& bin_uri) const {
    nlohmann::json d = doc;
    if (!bin.empty()) {
      d["buffers"] = {{{"byteLength", bin.size()}, {"uri", bin_uri}}};
    }
    return d.dump(1);
  }

  static void Put32(std::string& out, uint32_t v) {
    for (int i = 0; i < 4; ++i) out += static_cast<char>((v >> (8 * i)) & 0xff);
  }

  nlohmann::json doc;
  std::string bin;
};

// One triangle (0,0,0) (1,0,0) (0,1,0), indexed, in one node.
inline GltfBuilder OneTriangle() {
  GltfBuilder b;
  const int p = b.Positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
  const int i = b.Indices({0, 1, 2});
  b.Mesh({{{"attributes", {{"POSITION", p}}}, {"indices", i}}});
  b.Scene({b.Node({{"mesh", 0}})});
  return b;
}

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_CODEC_ASSET_GLTF_BUILDER_TESTONLY_H_
