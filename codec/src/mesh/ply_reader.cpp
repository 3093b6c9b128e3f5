// PLY entry point and the binary (little- and big-endian) body reader.
#include <algorithm>
#include <bit>
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "core/byte_reader.h"
#include "mesh/mesh_readers.h"
#include "mesh/ply_header.h"
#include "mesh/text_scanner.h"

namespace meshwave {
namespace {

double LoadAsDouble(const char* p, PlyScalar type, std::endian order) {
  switch (type) {
    case PlyScalar::kInt8:
      return LoadUnaligned<int8_t>(p, order);
    case PlyScalar::kUint8:
      return LoadUnaligned<uint8_t>(p, order);
    case PlyScalar::kInt16:
      return LoadUnaligned<int16_t>(p, order);
    case PlyScalar::kUint16:
      return LoadUnaligned<uint16_t>(p, order);
    case PlyScalar::kInt32:
      return LoadUnaligned<int32_t>(p, order);
    case PlyScalar::kUint32:
      return LoadUnaligned<uint32_t>(p, order);
    case PlyScalar::kFloat32:
      return LoadUnaligned<float>(p, order);
    case PlyScalar::kFloat64:
      return LoadUnaligned<double>(p, order);
  }
  return 0.0;
}

// Integer types only (the header guarantees it for counts and indices).
int64_t LoadAsInteger(const char* p, PlyScalar type, std::endian order) {
  switch (type) {
    case PlyScalar::kInt8:
      return LoadUnaligned<int8_t>(p, order);
    case PlyScalar::kUint8:
      return LoadUnaligned<uint8_t>(p, order);
    case PlyScalar::kInt16:
      return LoadUnaligned<int16_t>(p, order);
    case PlyScalar::kUint16:
      return LoadUnaligned<uint16_t>(p, order);
    case PlyScalar::kInt32:
      return LoadUnaligned<int32_t>(p, order);
    case PlyScalar::kUint32:
      return LoadUnaligned<uint32_t>(p, order);
    case PlyScalar::kFloat32:
    case PlyScalar::kFloat64:
      break;
  }
  return -1;
}

// Decodes x/y/z of `count` fixed-size records all stored as T: the hot loop
// for the common float-only vertex element.
template <class T>
void DecodeUniformCoordinates(const char* records, size_t count, size_t stride,
                              const size_t offsets[3], std::endian order,
                              Vec3* out) {
  for (size_t i = 0; i < count; ++i) {
    const char* record = records + i * stride;
    out[i] = Vec3(LoadUnaligned<T>(record + offsets[0], order),
                  LoadUnaligned<T>(record + offsets[1], order),
                  LoadUnaligned<T>(record + offsets[2], order));
  }
}

class BinaryBodyReader {
 public:
  BinaryBodyReader(const PlyHeader& header, std::string_view bytes,
                   std::string_view name, std::vector<Eigen::Vector4f>* colors)
      : header_(header),
        layout_(header.layout),
        name_(name),
        reader_(bytes.substr(header.body_offset)),
        order_(header.encoding == PlyEncoding::kBinaryBigEndian
                   ? std::endian::big
                   : std::endian::little),
        colors_(header.layout.HasColors() ? colors : nullptr) {}

  Result<TriMesh> Read() {
    for (size_t i = 0; i < header_.elements.size(); ++i) {
      const PlyElement& e = header_.elements[i];
      if (i == layout_.vertex_element) {
        MW_RETURN_IF_ERROR(ReadVertices(e));
      } else if (i == layout_.face_element) {
        MW_RETURN_IF_ERROR(ReadFaces(e));
      } else {
        MW_RETURN_IF_ERROR(SkipElement(e));
      }
    }
    std::string_view rest = reader_.rest();
    for (char c : rest) {
      if (!IsSpace(c)) {
        std::string where = header_.elements.empty()
                                ? LineWhere(header_.body_line)
                                : "element " + header_.elements.back().name;
        return MeshParseError(name_, where,
                              std::to_string(rest.size()) +
                                  " unexpected bytes after the last record");
      }
    }
    return std::move(mesh_);
  }

 private:
  // Refuses a count the remaining bytes cannot hold, before any loop or
  // allocation sized by it.
  Status CheckCount(const PlyElement& e) const {
    std::optional<size_t> need = CheckedMul(e.count, e.MinBinaryRecordSize());
    if (!need || *need > reader_.remaining()) {
      return MeshParseError(
          name_, "element " + e.name,
          std::to_string(e.count) + " records need at least " +
              (need ? std::to_string(*need) : std::string("2^64")) +
              " bytes but only " + std::to_string(reader_.remaining()) +
              " remain");
    }
    return Status::Ok();
  }

  Status Truncated(const PlyElement& e, uint64_t record) const {
    return MeshParseError(name_, e.name + " " + std::to_string(record),
                          "truncated data (file ends inside the record)");
  }

  // Reads one record of `e`, calling on_scalar(property, bytes) for scalars
  // and on_list(property, count, bytes of the items) for lists.
  template <class OnScalar, class OnList>
  Status WalkRecord(const PlyElement& e, uint64_t record, OnScalar on_scalar,
                    OnList on_list) {
    for (size_t p = 0; p < e.properties.size(); ++p) {
      const PlyProperty& property = e.properties[p];
      std::string_view data;
      if (!property.is_list) {
        if (!reader_.ReadBytes(PlyScalarSize(property.type), &data)) {
          return Truncated(e, record);
        }
        MW_RETURN_IF_ERROR(on_scalar(p, data.data()));
        continue;
      }
      if (!reader_.ReadBytes(PlyScalarSize(property.count_type), &data)) {
        return Truncated(e, record);
      }
      int64_t count = LoadAsInteger(data.data(), property.count_type, order_);
      if (count < 0) {
        return MeshParseError(name_, e.name + " " + std::to_string(record),
                              "negative list length " + std::to_string(count));
      }
      // count < 2^32 and item sizes are at most 8: no overflow.
      size_t size = static_cast<size_t>(count) * PlyScalarSize(property.type);
      if (!reader_.ReadBytes(size, &data)) return Truncated(e, record);
      MW_RETURN_IF_ERROR(on_list(p, static_cast<size_t>(count), data.data()));
    }
    return Status::Ok();
  }

  Status SkipElement(const PlyElement& e) {
    MW_RETURN_IF_ERROR(CheckCount(e));
    if (!e.HasLists()) {
      reader_.Skip(e.count * e.MinBinaryRecordSize());  // checked above
      return Status::Ok();
    }
    auto ignore_scalar = [](size_t, const char*) { return Status::Ok(); };
    auto ignore_list = [](size_t, size_t, const char*) { return Status::Ok(); };
    for (uint64_t r = 0; r < e.count; ++r) {
      MW_RETURN_IF_ERROR(WalkRecord(e, r, ignore_scalar, ignore_list));
    }
    return Status::Ok();
  }

  // Stores colour channel property p of vertex r, when p is one.
  Status MaybeColor(const PlyElement& e, size_t r, size_t p, const char* data) {
    for (int c = 0; c < 4; ++c) {
      if (p != layout_.rgba[c]) continue;
      const double value = LoadAsDouble(data, e.properties[p].type, order_);
      if (std::isnan(value)) {
        return MeshParseError(name_, "vertex " + std::to_string(r),
                              "colour is NaN");
      }
      (*colors_)[r][c] = PlyColorChannel(value, e.properties[p].type);
    }
    return Status::Ok();
  }

  Status ReadVertices(const PlyElement& e) {
    MW_RETURN_IF_ERROR(CheckCount(e));
    const size_t count = static_cast<size_t>(e.count);
    mesh_.positions.resize(count);
    if (colors_ != nullptr) {
      colors_->assign(count, Eigen::Vector4f(1.0f, 1.0f, 1.0f, 1.0f));
    }
    if (!e.HasLists()) {
      MW_RETURN_IF_ERROR(ReadFixedVertices(e));
    } else {
      for (size_t r = 0; r < count; ++r) {
        Vec3& position = mesh_.positions[r];
        auto on_scalar = [&](size_t p, const char* data) {
          for (int axis = 0; axis < 3; ++axis) {
            if (p == layout_.xyz[axis]) {
              position[axis] = LoadAsDouble(data, e.properties[p].type, order_);
            }
          }
          if (colors_ != nullptr) return MaybeColor(e, r, p, data);
          return Status::Ok();
        };
        auto ignore_list = [](size_t, size_t, const char*) {
          return Status::Ok();
        };
        MW_RETURN_IF_ERROR(WalkRecord(e, r, on_scalar, ignore_list));
      }
    }
    for (size_t r = 0; r < count; ++r) {
      if (!mesh_.positions[r].allFinite()) {
        return MeshParseError(name_, "vertex " + std::to_string(r),
                              "coordinate is NaN or infinite");
      }
    }
    return Status::Ok();
  }

  // Records without lists have one size: take them all at once and decode
  // x/y/z at precomputed offsets.
  Status ReadFixedVertices(const PlyElement& e) {
    const size_t stride = e.MinBinaryRecordSize();
    std::string_view records;
    if (!reader_.ReadBytes(mesh_.positions.size() * stride, &records)) {
      return Truncated(e, 0);  // unreachable after CheckCount
    }
    size_t offsets[3] = {0, 0, 0};
    PlyScalar types[3] = {};
    size_t offset = 0;
    for (size_t p = 0; p < e.properties.size(); ++p) {
      for (int axis = 0; axis < 3; ++axis) {
        if (p == layout_.xyz[axis]) {
          offsets[axis] = offset;
          types[axis] = e.properties[p].type;
        }
      }
      offset += PlyScalarSize(e.properties[p].type);
    }
    Vec3* out = mesh_.positions.data();
    const size_t count = mesh_.positions.size();
    const bool uniform = types[0] == types[1] && types[1] == types[2];
    if (uniform && types[0] == PlyScalar::kFloat32) {
      DecodeUniformCoordinates<float>(records.data(), count, stride, offsets,
                                      order_, out);
    } else if (uniform && types[0] == PlyScalar::kFloat64) {
      DecodeUniformCoordinates<double>(records.data(), count, stride, offsets,
                                       order_, out);
    } else {
      for (size_t r = 0; r < count; ++r) {
        const char* record = records.data() + r * stride;
        for (int axis = 0; axis < 3; ++axis) {
          out[r][axis] =
              LoadAsDouble(record + offsets[axis], types[axis], order_);
        }
      }
    }
    if (colors_ != nullptr) {
      // A second pass over the same records: the geometry loop above stays
      // as fast as without colours.
      size_t property_offsets[4] = {0, 0, 0, 0};
      for (int c = 0; c < 4; ++c) {
        if (layout_.rgba[c] == PlyMeshLayout::kNone) continue;
        size_t at = 0;
        for (size_t p = 0; p < layout_.rgba[c]; ++p) {
          at += PlyScalarSize(e.properties[p].type);
        }
        property_offsets[c] = at;
      }
      for (size_t r = 0; r < count; ++r) {
        const char* record = records.data() + r * stride;
        for (int c = 0; c < 4; ++c) {
          if (layout_.rgba[c] == PlyMeshLayout::kNone) continue;
          MW_RETURN_IF_ERROR(
              MaybeColor(e, r, layout_.rgba[c], record + property_offsets[c]));
        }
      }
    }
    return Status::Ok();
  }

  Status ReadFaces(const PlyElement& e) {
    MW_RETURN_IF_ERROR(CheckCount(e));
    const PlyProperty& indices = e.properties[layout_.indices];
    // Reserve for triangles only as many as the bytes can hold, so a large
    // count of empty lists cannot make a large allocation.
    size_t triangle_size =
        e.MinBinaryRecordSize() + 3 * PlyScalarSize(indices.type);
    mesh_.faces.reserve(
        std::min<size_t>(e.count, reader_.remaining() / triangle_size));
    const size_t index_size = PlyScalarSize(indices.type);
    auto ignore_scalar = [](size_t, const char*) { return Status::Ok(); };
    for (uint64_t r = 0; r < e.count; ++r) {
      auto on_list = [&](size_t p, size_t n, const char* items) {
        if (p != layout_.indices) return Status::Ok();
        if (n < 3) {
          return MeshParseError(name_, "face " + std::to_string(r),
                                "polygon with " + std::to_string(n) +
                                    " corners (at least 3 needed)");
        }
        uint32_t corners[3] = {0, 0, 0};
        for (size_t k = 0; k < n; ++k) {
          int64_t index =
              LoadAsInteger(items + k * index_size, indices.type, order_);
          if (index < 0 ||
              static_cast<uint64_t>(index) >= layout_.vertex_count) {
            return IndexError(r, index);
          }
          corners[k < 2 ? k : 2] = static_cast<uint32_t>(index);
          if (k >= 2) {
            mesh_.faces.push_back({corners[0], corners[1], corners[2]});
            corners[1] = corners[2];  // fan around the first corner
          }
        }
        return Status::Ok();
      };
      MW_RETURN_IF_ERROR(WalkRecord(e, r, ignore_scalar, on_list));
    }
    return Status::Ok();
  }

  Status IndexError(uint64_t face, int64_t index) const {
    std::string what =
        index < 0
            ? "negative vertex index " + std::to_string(index)
            : "vertex index " + std::to_string(index) + " out of range (" +
                  std::to_string(layout_.vertex_count) + " vertices)";
    return MeshParseError(name_, "face " + std::to_string(face), what);
  }

  const PlyHeader& header_;
  const PlyMeshLayout& layout_;
  std::string_view name_;
  ByteReader reader_;
  std::endian order_;
  std::vector<Eigen::Vector4f>* colors_;  // null: geometry only
  TriMesh mesh_;
};

}  // namespace

Result<TriMesh> ReadPlyBinaryBody(const PlyHeader& header,
                                  std::string_view bytes, std::string_view name,
                                  std::vector<Eigen::Vector4f>* colors) {
  return BinaryBodyReader(header, bytes, name, colors).Read();
}

Result<PlyColoredMesh> ParsePlyWithColors(std::string_view bytes,
                                          std::string_view name) {
  PlyColoredMesh out;
  MW_ASSIGN_OR_RETURN(out.header, ParsePlyHeader(bytes, name));
  if (out.header.encoding == PlyEncoding::kAscii) {
    MW_ASSIGN_OR_RETURN(out.mesh,
                        ReadPlyAsciiBody(out.header, bytes, name, &out.colors));
  } else {
    MW_ASSIGN_OR_RETURN(out.mesh,
                        ReadPlyBinaryBody(out.header, bytes, name, &out.colors));
  }
  return out;
}

Result<TriMesh> ParsePly(std::string_view bytes, std::string_view name) {
  MW_ASSIGN_OR_RETURN(PlyHeader header, ParsePlyHeader(bytes, name));
  if (header.encoding == PlyEncoding::kAscii) {
    return ReadPlyAsciiBody(header, bytes, name);
  }
  return ReadPlyBinaryBody(header, bytes, name);
}

}  // namespace meshwave
