// The ASCII PLY body reader: whitespace-separated values, records usually
// one per line (not required), every value checked against its declared type.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>

#include "core/byte_reader.h"
#include "mesh/mesh_readers.h"
#include "mesh/ply_header.h"
#include "mesh/text_scanner.h"

namespace meshwave {
namespace {

bool IntegerFits(int64_t value, PlyScalar type) {
  switch (type) {
    case PlyScalar::kInt8:
      return value >= -128 && value <= 127;
    case PlyScalar::kUint8:
      return value >= 0 && value <= 255;
    case PlyScalar::kInt16:
      return value >= -32768 && value <= 32767;
    case PlyScalar::kUint16:
      return value >= 0 && value <= 65535;
    case PlyScalar::kInt32:
      return value >= INT32_MIN && value <= INT32_MAX;
    case PlyScalar::kUint32:
      return value >= 0 && value <= UINT32_MAX;
    case PlyScalar::kFloat32:
    case PlyScalar::kFloat64:
      return true;
  }
  return false;
}

class AsciiBodyReader {
 public:
  AsciiBodyReader(const PlyHeader& header, std::string_view bytes,
                  std::string_view name, std::vector<Eigen::Vector4f>* colors)
      : header_(header),
        layout_(header.layout),
        name_(name),
        cursor_(bytes.substr(header.body_offset), header.body_line),
        colors_(header.layout.HasColors() ? colors : nullptr) {}

  Result<TriMesh> Read() {
    for (size_t i = 0; i < header_.elements.size(); ++i) {
      const PlyElement& e = header_.elements[i];
      MW_RETURN_IF_ERROR(CheckCount(e));
      if (i == layout_.vertex_element) {
        MW_RETURN_IF_ERROR(ReadVertices(e));
      } else if (i == layout_.face_element) {
        MW_RETURN_IF_ERROR(ReadFaces(e));
      } else if (!e.properties.empty()) {  // else its records hold nothing
        for (uint64_t r = 0; r < e.count; ++r) {
          MW_RETURN_IF_ERROR(SkipRecord(e, r));
        }
      }
    }
    std::string_view extra;
    if (cursor_.Next(&extra)) {
      return MeshParseError(
          name_, LineWhere(cursor_.line()),
          "unexpected " + Quoted(extra) + " after the last element");
    }
    return std::move(mesh_);
  }

 private:
  // Every value takes a character and a separator (the very last one may
  // lack the separator), so a count is refused when the rest of the file
  // cannot hold that many values.
  Status CheckCount(const PlyElement& e) const {
    std::optional<size_t> values = CheckedMul(e.count, e.properties.size());
    std::optional<size_t> need = values ? CheckedMul(*values, 2) : std::nullopt;
    if (!need || *need > cursor_.remaining() + 1) {
      return MeshParseError(
          name_, "element " + e.name,
          std::to_string(e.count) + " records cannot fit in the " +
              std::to_string(cursor_.remaining()) + " bytes that remain");
    }
    return Status::Ok();
  }

  Status Error(const PlyElement& e, uint64_t record,
               const std::string& what) const {
    return MeshParseError(name_,
                          LineWhere(cursor_.line()) + ": " + e.name + " " +
                              std::to_string(record),
                          what);
  }

  Status NextToken(const PlyElement& e, uint64_t record,
                   std::string_view* token) {
    if (!cursor_.Next(token)) return Error(e, record, "unexpected end of file");
    return Status::Ok();
  }

  // Reads one value of `type` as a double (integers exactly).
  Status ReadValue(const PlyElement& e, uint64_t record, PlyScalar type,
                   double* value) {
    std::string_view token;
    MW_RETURN_IF_ERROR(NextToken(e, record, &token));
    if (!IsIntegerScalar(type)) {
      if (!ParseDouble(token, value))
        return Error(e, record, "bad number " + Quoted(token));
      return Status::Ok();
    }
    int64_t integer = 0;
    MW_RETURN_IF_ERROR(ReadIntegerToken(e, record, type, token, &integer));
    *value = static_cast<double>(integer);
    return Status::Ok();
  }

  Status ReadInteger(const PlyElement& e, uint64_t record, PlyScalar type,
                     int64_t* value) {
    std::string_view token;
    MW_RETURN_IF_ERROR(NextToken(e, record, &token));
    return ReadIntegerToken(e, record, type, token, value);
  }

  Status ReadIntegerToken(const PlyElement& e, uint64_t record, PlyScalar type,
                          std::string_view token, int64_t* value) {
    if (!ParseInt64(token, value)) {
      return Error(e, record, "bad integer " + Quoted(token));
    }
    if (!IntegerFits(*value, type)) {
      return Error(
          e, record,
          std::to_string(*value) + " does not fit in " + PlyScalarName(type));
    }
    return Status::Ok();
  }

  // Reads a list length; each item takes at least one byte of what remains.
  Status ReadListCount(const PlyElement& e, uint64_t record,
                       const PlyProperty& property, size_t* count) {
    int64_t value = 0;
    MW_RETURN_IF_ERROR(ReadInteger(e, record, property.count_type, &value));
    if (value < 0) {
      return Error(e, record, "negative list length " + std::to_string(value));
    }
    if (static_cast<uint64_t>(value) > cursor_.remaining()) {
      return Error(e, record,
                   "list of " + std::to_string(value) +
                       " items cannot fit in the rest of the file");
    }
    *count = static_cast<size_t>(value);
    return Status::Ok();
  }

  Status SkipProperty(const PlyElement& e, uint64_t record,
                      const PlyProperty& property) {
    double ignored = 0.0;
    if (!property.is_list) return ReadValue(e, record, property.type, &ignored);
    size_t count = 0;
    MW_RETURN_IF_ERROR(ReadListCount(e, record, property, &count));
    for (size_t k = 0; k < count; ++k) {
      MW_RETURN_IF_ERROR(ReadValue(e, record, property.type, &ignored));
    }
    return Status::Ok();
  }

  Status SkipRecord(const PlyElement& e, uint64_t record) {
    for (const PlyProperty& property : e.properties) {
      MW_RETURN_IF_ERROR(SkipProperty(e, record, property));
    }
    return Status::Ok();
  }

  // Which colour channel property p holds, or -1.
  int ColorChannel(size_t p) const {
    if (colors_ == nullptr) return -1;
    for (int c = 0; c < 4; ++c) {
      if (p == layout_.rgba[c]) return c;
    }
    return -1;
  }

  Status ReadVertices(const PlyElement& e) {
    mesh_.positions.resize(static_cast<size_t>(e.count));  // checked count
    if (colors_ != nullptr) {
      colors_->assign(static_cast<size_t>(e.count),
                      Eigen::Vector4f(1.0f, 1.0f, 1.0f, 1.0f));
    }
    for (uint64_t r = 0; r < e.count; ++r) {
      Vec3& position = mesh_.positions[r];
      for (size_t p = 0; p < e.properties.size(); ++p) {
        const PlyProperty& property = e.properties[p];
        int axis = p == layout_.xyz[0]   ? 0
                   : p == layout_.xyz[1] ? 1
                   : p == layout_.xyz[2] ? 2
                                         : -1;
        if (const int channel = axis < 0 ? ColorChannel(p) : -1; channel >= 0) {
          double value = 0.0;
          MW_RETURN_IF_ERROR(ReadValue(e, r, property.type, &value));
          if (std::isnan(value)) return Error(e, r, "colour is NaN");
          (*colors_)[r][channel] = PlyColorChannel(value, property.type);
          continue;
        }
        if (axis < 0) {
          MW_RETURN_IF_ERROR(SkipProperty(e, r, property));
          continue;
        }
        MW_RETURN_IF_ERROR(ReadValue(e, r, property.type, &position[axis]));
        if (!std::isfinite(position[axis])) {
          return Error(e, r, "coordinate is NaN or infinite");
        }
      }
    }
    return Status::Ok();
  }

  Status ReadFaces(const PlyElement& e) {
    // Triangles need at least four values of two bytes each.
    mesh_.faces.reserve(std::min<size_t>(e.count, cursor_.remaining() / 8));
    for (uint64_t r = 0; r < e.count; ++r) {
      for (size_t p = 0; p < e.properties.size(); ++p) {
        const PlyProperty& property = e.properties[p];
        if (p != layout_.indices) {
          MW_RETURN_IF_ERROR(SkipProperty(e, r, property));
          continue;
        }
        size_t n = 0;
        MW_RETURN_IF_ERROR(ReadListCount(e, r, property, &n));
        if (n < 3) {
          return Error(e, r,
                       "polygon with " + std::to_string(n) +
                           " corners (at least 3 needed)");
        }
        uint32_t corners[3] = {0, 0, 0};
        for (size_t k = 0; k < n; ++k) {
          int64_t index = 0;
          MW_RETURN_IF_ERROR(ReadInteger(e, r, property.type, &index));
          if (index < 0) {
            return Error(e, r,
                         "negative vertex index " + std::to_string(index));
          }
          if (static_cast<uint64_t>(index) >= layout_.vertex_count) {
            return Error(
                e, r,
                "vertex index " + std::to_string(index) + " out of range (" +
                    std::to_string(layout_.vertex_count) + " vertices)");
          }
          corners[k < 2 ? k : 2] = static_cast<uint32_t>(index);
          if (k >= 2) {
            mesh_.faces.push_back({corners[0], corners[1], corners[2]});
            corners[1] = corners[2];  // fan around the first corner
          }
        }
      }
    }
    return Status::Ok();
  }

  const PlyHeader& header_;
  const PlyMeshLayout& layout_;
  std::string_view name_;
  TokenCursor cursor_;
  std::vector<Eigen::Vector4f>* colors_;  // null: geometry only
  TriMesh mesh_;
};

}  // namespace

Result<TriMesh> ReadPlyAsciiBody(const PlyHeader& header,
                                 std::string_view bytes, std::string_view name,
                                 std::vector<Eigen::Vector4f>* colors) {
  return AsciiBodyReader(header, bytes, name, colors).Read();
}

}  // namespace meshwave
