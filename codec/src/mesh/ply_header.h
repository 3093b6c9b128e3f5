// PlyHeader: the parsed header of a PLY file (encoding, elements and their
// properties) and where in it the mesh lives. Shared by the ASCII and the
// binary body readers.
#ifndef MESHWAVE_MESH_PLY_HEADER_H_
#define MESHWAVE_MESH_PLY_HEADER_H_

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "meshwave/mesh.h"
#include "meshwave/status.h"

namespace meshwave {

enum class PlyScalar : uint8_t {
  kInt8,
  kUint8,
  kInt16,
  kUint16,
  kInt32,
  kUint32,
  kFloat32,
  kFloat64,
};

size_t PlyScalarSize(PlyScalar type);
const char* PlyScalarName(PlyScalar type);
inline bool IsIntegerScalar(PlyScalar type) {
  return type != PlyScalar::kFloat32 && type != PlyScalar::kFloat64;
}

enum class PlyEncoding { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

struct PlyProperty {
  std::string name;
  PlyScalar type = PlyScalar::kFloat32;  // of the value, or of list items
  bool is_list = false;
  PlyScalar count_type = PlyScalar::kUint8;  // lists only
};

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<PlyProperty> properties;
  size_t line = 0;  // header line that declared it

  bool HasLists() const;
  // Bytes of one binary record when every list is empty (the exact size
  // when there are no lists).
  size_t MinBinaryRecordSize() const;
};

// Where the triangle mesh lives in the elements of a header.
struct PlyMeshLayout {
  static constexpr size_t kNone = static_cast<size_t>(-1);
  size_t vertex_element = kNone;
  size_t xyz[3] = {kNone, kNone, kNone};  // property indices of x, y, z
  size_t face_element = kNone;
  size_t indices = kNone;  // property index of vertex_indices
  uint64_t vertex_count = 0;
  // Vertex colour properties (red, green, blue, alpha, or diffuse_red ...),
  // scalars; kNone when absent. Colours are read only when red, green and
  // blue are all there.
  size_t rgba[4] = {kNone, kNone, kNone, kNone};
  bool HasColors() const {
    return rgba[0] != kNone && rgba[1] != kNone && rgba[2] != kNone;
  }
};

struct PlyHeader {
  PlyEncoding encoding = PlyEncoding::kAscii;
  std::vector<PlyElement> elements;
  PlyMeshLayout layout;
  size_t body_offset = 0;  // first byte after the end_header line
  size_t body_line = 0;    // number of the line that starts there
};

// Parses and checks the header: magic, format line, element and property
// declarations, and that a vertex element with x/y/z scalars and a face
// element with an integer vertex_indices (or vertex_index) list exist.
// Safe on untrusted bytes; errors name `name` and the header line.
Result<PlyHeader> ParsePlyHeader(std::string_view bytes, std::string_view name);

// The body readers, one per encoding: they read the elements of `header`
// from `bytes` (the whole file) starting at header.body_offset. With
// `colors` (and header.layout.HasColors()) they also fill one colour per
// vertex, see PlyColorChannel; without, they read geometry alone, as fast
// as before colours existed.
Result<TriMesh> ReadPlyAsciiBody(const PlyHeader& header,
                                 std::string_view bytes, std::string_view name,
                                 std::vector<Eigen::Vector4f>* colors = nullptr);
Result<TriMesh> ReadPlyBinaryBody(
    const PlyHeader& header, std::string_view bytes, std::string_view name,
    std::vector<Eigen::Vector4f>* colors = nullptr);

// A colour channel as stored, mapped to [0, 1] by its type: integers
// divided by their type's maximum (uchar 255, ushort 65535, ...), floats
// as they are; clamped. No transfer function is applied (PLY colours are
// sRGB-encoded by convention: the caller decodes them).
float PlyColorChannel(double value, PlyScalar type);

// ParsePly with the vertex colours (empty when the file has none) and the
// header, for a caller that reports what else the file holds.
struct PlyColoredMesh {
  TriMesh mesh;
  std::vector<Eigen::Vector4f> colors;
  PlyHeader header;
};
Result<PlyColoredMesh> ParsePlyWithColors(std::string_view bytes,
                                          std::string_view name);

}  // namespace meshwave

#endif  // MESHWAVE_MESH_PLY_HEADER_H_
