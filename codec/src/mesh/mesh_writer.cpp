// The in-memory writers: binary little-endian PLY, OBJ and glTF 2.0.
#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <cstring>
#include <string>

#include "core/base64.h"
#include "core/byte_reader.h"
#include "meshwave/gltf.h"
#include "meshwave/mesh.h"

namespace meshwave {
namespace {

template <class T>
char* StoreLittleEndian(char* out, T value) {
  if constexpr (std::endian::native != std::endian::little) {
    value = ByteSwapped(value);
  }
  std::memcpy(out, &value, sizeof(T));
  return out + sizeof(T);
}

// Appends the shortest decimal form that reads back as the same double;
// never more than 17 significant digits.
void AppendDouble(std::string& out, double value) {
  char buffer[32];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out.append(buffer, end);  // 32 bytes always suffice for a double
}

void AppendUnsigned(std::string& out, uint64_t value) {
  char buffer[24];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out.append(buffer, end);
}

void AppendFloatArray(std::string& out, const std::array<float, 3>& v) {
  out += '[';
  for (int a = 0; a < 3; ++a) {
    if (a) out += ',';
    // float -> double is exact and the shortest double form reads back as
    // the same float: min/max equal the data bit for bit, as glTF asks.
    AppendDouble(out, v[a]);
  }
  out += ']';
}

void PadTo4(std::string& s, char pad) { s.append((4 - s.size() % 4) % 4, pad); }

// Linear [0, 1] (clamped) to an sRGB-encoded byte (IEC 61966-2-1).
uint8_t LinearToSrgbByte(double linear) {
  const double v = std::clamp(linear, 0.0, 1.0);
  const double encoded = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055;
  return static_cast<uint8_t>(std::lround(255 * std::clamp(encoded, 0.0, 1.0)));
}

void AppendUint32(std::string& out, uint32_t v) {
  char bytes[4];
  StoreLittleEndian(bytes, v);
  out.append(bytes, 4);
}

}  // namespace

std::optional<GltfForm> GltfFormFromPath(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".glb") return GltfForm::kBinary;
  if (ext == ".gltf") return GltfForm::kEmbedded;
  return std::nullopt;
}

std::string SerializeGltf(const TriMesh& mesh, GltfForm form, std::span<const Vec3> colors) {
  // The buffer: float32 positions, then uint32 indices, then float32
  // colours (all 4-aligned).
  const size_t n = mesh.positions.size();
  const bool colored = !colors.empty() && colors.size() == n;
  std::string bin(n * 12 + mesh.faces.size() * 12 + (colored ? n * 12 : 0), '\0');
  char* p = bin.data();
  std::array<float, 3> lo, hi;
  lo.fill(std::numeric_limits<float>::infinity());
  hi.fill(-std::numeric_limits<float>::infinity());
  for (const Vec3& v : mesh.positions) {
    for (int a = 0; a < 3; ++a) {
      const float f = static_cast<float>(v[a]);
      lo[a] = std::min(lo[a], f);
      hi[a] = std::max(hi[a], f);
      p = StoreLittleEndian(p, f);
    }
  }
  for (const Face& f : mesh.faces) {
    for (uint32_t index : f) p = StoreLittleEndian(p, index);
  }
  if (colored) {
    for (const Vec3& c : colors) {
      for (int a = 0; a < 3; ++a) {
        p = StoreLittleEndian(p, static_cast<float>(std::clamp(c[a], 0.0, 1.0)));
      }
    }
  }

  std::string json = R"({"asset":{"version":"2.0","generator":"meshwave"},"scene":0,)";
  if (mesh.faces.empty() || n == 0) {
    // glTF forbids empty buffers and accessors: an empty scene instead.
    json += R"("scenes":[{"nodes":[]}]})";
    bin.clear();
  } else {
    json += R"("scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)";
    json += colored
                ? R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"COLOR_0":2},"indices":1,"mode":4}]}],)"
                : R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1,"mode":4}]}],)";
    json += R"("accessors":[{"bufferView":0,"componentType":5126,"count":)";
    AppendUnsigned(json, n);
    json += R"(,"type":"VEC3","min":)";
    AppendFloatArray(json, lo);
    json += R"(,"max":)";
    AppendFloatArray(json, hi);
    json += R"(},{"bufferView":1,"componentType":5125,"count":)";
    AppendUnsigned(json, mesh.faces.size() * 3);
    json += R"(,"type":"SCALAR"})";
    if (colored) {
      json += R"(,{"bufferView":2,"componentType":5126,"count":)";
      AppendUnsigned(json, n);
      json += R"(,"type":"VEC3"})";
    }
    json += R"(],"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":)";
    AppendUnsigned(json, n * 12);
    json += R"(,"target":34962},{"buffer":0,"byteOffset":)";
    AppendUnsigned(json, n * 12);
    json += R"(,"byteLength":)";
    AppendUnsigned(json, mesh.faces.size() * 12);
    json += R"(,"target":34963})";
    if (colored) {
      json += R"(,{"buffer":0,"byteOffset":)";
      AppendUnsigned(json, n * 12 + mesh.faces.size() * 12);
      json += R"(,"byteLength":)";
      AppendUnsigned(json, n * 12);
      json += R"(,"target":34962})";
    }
    json += R"(],"buffers":[{"byteLength":)";
    AppendUnsigned(json, bin.size());
    if (form == GltfForm::kEmbedded) {
      json += R"(,"uri":"data:application/octet-stream;base64,)";
      json += Base64(bin);
      json += '"';
    }
    json += "}]}";
  }
  if (form == GltfForm::kEmbedded) return json + "\n";

  // GLB: a 12-byte header, the JSON chunk (space-padded), the BIN chunk.
  PadTo4(json, ' ');
  PadTo4(bin, '\0');
  const size_t total = 12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin.size());
  std::string out;
  out.reserve(total);
  AppendUint32(out, 0x46546C67);  // "glTF"
  AppendUint32(out, 2);
  AppendUint32(out, static_cast<uint32_t>(total));
  AppendUint32(out, static_cast<uint32_t>(json.size()));
  AppendUint32(out, 0x4E4F534A);  // "JSON"
  out += json;
  if (!bin.empty()) {
    AppendUint32(out, static_cast<uint32_t>(bin.size()));
    AppendUint32(out, 0x004E4942);  // "BIN\0"
    out += bin;
  }
  return out;
}

std::string SerializePly(const TriMesh& mesh, std::span<const Vec3> colors) {
  const bool colored = !colors.empty() && colors.size() == mesh.positions.size();
  std::string out =
      "ply\n"
      "format binary_little_endian 1.0\n"
      "comment written by meshwave\n"
      "element vertex " +
      std::to_string(mesh.positions.size()) +
      "\n"
      "property float x\n"
      "property float y\n"
      "property float z\n" +
      std::string(colored ? "property uchar red\nproperty uchar green\nproperty uchar blue\n"
                          : "") +
      "element face " +
      std::to_string(mesh.faces.size()) +
      "\n"
      "property list uchar int vertex_indices\n"
      "end_header\n";
  const size_t header_size = out.size();
  const size_t vertex_bytes = 3 * sizeof(float) + (colored ? 3 : 0);
  constexpr size_t kFaceBytes = 1 + 3 * sizeof(int32_t);
  out.resize(header_size + mesh.positions.size() * vertex_bytes +
             mesh.faces.size() * kFaceBytes);
  char* p = out.data() + header_size;
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      p = StoreLittleEndian(p, static_cast<float>(mesh.positions[i][axis]));
    }
    if (colored) {
      for (int c = 0; c < 3; ++c) *p++ = static_cast<char>(LinearToSrgbByte(colors[i][c]));
    }
  }
  for (const Face& f : mesh.faces) {
    *p++ = 3;
    for (uint32_t index : f)
      p = StoreLittleEndian(p, static_cast<int32_t>(index));
  }
  return out;
}

std::string SerializeObj(const TriMesh& mesh) {
  std::string out = "# written by meshwave\n";
  // Roughly 60 bytes per vertex line and 25 per face line.
  out.reserve(out.size() + mesh.positions.size() * 60 + mesh.faces.size() * 25);
  for (const Vec3& v : mesh.positions) {
    out += 'v';
    for (int axis = 0; axis < 3; ++axis) {
      out += ' ';
      AppendDouble(out, v[axis]);
    }
    out += '\n';
  }
  for (const Face& f : mesh.faces) {
    out += 'f';
    for (uint32_t index : f) {
      out += ' ';
      AppendUnsigned(out, uint64_t{index} + 1);
    }
    out += '\n';
  }
  return out;
}

}  // namespace meshwave
