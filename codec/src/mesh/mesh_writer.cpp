// The in-memory writers: binary little-endian PLY and OBJ.
#include <bit>
#include <charconv>
#include <cstring>
#include <string>

#include "core/byte_reader.h"
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

}  // namespace

std::string SerializePly(const TriMesh& mesh) {
  std::string out =
      "ply\n"
      "format binary_little_endian 1.0\n"
      "comment written by meshwave\n"
      "element vertex " +
      std::to_string(mesh.positions.size()) +
      "\n"
      "property float x\n"
      "property float y\n"
      "property float z\n"
      "element face " +
      std::to_string(mesh.faces.size()) +
      "\n"
      "property list uchar int vertex_indices\n"
      "end_header\n";
  const size_t header_size = out.size();
  constexpr size_t kVertexBytes = 3 * sizeof(float);
  constexpr size_t kFaceBytes = 1 + 3 * sizeof(int32_t);
  out.resize(header_size + mesh.positions.size() * kVertexBytes +
             mesh.faces.size() * kFaceBytes);
  char* p = out.data() + header_size;
  for (const Vec3& v : mesh.positions) {
    for (int axis = 0; axis < 3; ++axis) {
      p = StoreLittleEndian(p, static_cast<float>(v[axis]));
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
