#include "mesh/ply_header.h"

#include <array>
#include <optional>
#include <utility>

#include "mesh/mesh_readers.h"
#include "mesh/text_scanner.h"

namespace meshwave {
namespace {

struct ScalarSpelling {
  std::string_view name;
  PlyScalar type;
};

// Both the classic names and the sized aliases are in use.
constexpr std::array<ScalarSpelling, 16> kScalarSpellings = {{
    {"char", PlyScalar::kInt8},
    {"int8", PlyScalar::kInt8},
    {"uchar", PlyScalar::kUint8},
    {"uint8", PlyScalar::kUint8},
    {"short", PlyScalar::kInt16},
    {"int16", PlyScalar::kInt16},
    {"ushort", PlyScalar::kUint16},
    {"uint16", PlyScalar::kUint16},
    {"int", PlyScalar::kInt32},
    {"int32", PlyScalar::kInt32},
    {"uint", PlyScalar::kUint32},
    {"uint32", PlyScalar::kUint32},
    {"float", PlyScalar::kFloat32},
    {"float32", PlyScalar::kFloat32},
    {"double", PlyScalar::kFloat64},
    {"float64", PlyScalar::kFloat64},
}};

std::optional<PlyScalar> ScalarFromName(std::string_view name) {
  for (const ScalarSpelling& s : kScalarSpellings) {
    if (s.name == name) return s.type;
  }
  return std::nullopt;
}

// Collects the tokens of one header line (a PLY header line has at most a
// handful; more are an error for every keyword that cares).
struct HeaderLine {
  static constexpr size_t kMaxTokens = 6;
  std::array<std::string_view, kMaxTokens> tokens;
  size_t size = 0;
  bool overflow = false;

  explicit HeaderLine(std::string_view line) {
    TokenSplitter splitter(line);
    std::string_view token;
    while (splitter.Next(&token)) {
      if (size == kMaxTokens) {
        overflow = true;
        break;
      }
      tokens[size++] = token;
    }
  }
};

class HeaderParser {
 public:
  HeaderParser(std::string_view bytes, std::string_view name)
      : name_(name), lines_(bytes) {}

  Result<PlyHeader> Parse() {
    std::string_view line;
    if (!lines_.Next(&line) || line != "ply") {
      return MeshParseError(name_, "line 1",
                            "not a PLY file (no \"ply\" magic)");
    }
    bool have_format = false;
    while (true) {
      if (!lines_.Next(&line)) {
        return MeshParseError(name_, LineWhere(lines_.number() + 1),
                              "header ends without end_header");
      }
      HeaderLine h(line);
      if (h.size == 0) continue;  // tolerated: blank header line
      std::string_view keyword = h.tokens[0];
      if (keyword == "comment" || keyword == "obj_info") continue;
      if (keyword == "end_header") break;
      if (keyword == "format") {
        MW_RETURN_IF_ERROR(ParseFormat(h, have_format));
        have_format = true;
      } else if (keyword == "element") {
        MW_RETURN_IF_ERROR(ParseElement(h));
      } else if (keyword == "property") {
        MW_RETURN_IF_ERROR(ParseProperty(h));
      } else {
        return Error("unknown header keyword " + Quoted(keyword));
      }
    }
    if (!have_format) return Error("end_header before any format line");
    header_.body_offset = lines_.position();
    header_.body_line = lines_.number() + 1;
    MW_RETURN_IF_ERROR(FindMesh());
    return std::move(header_);
  }

 private:
  Status Error(const std::string& what) const {
    return MeshParseError(name_, LineWhere(lines_.number()), what);
  }

  Status ParseFormat(const HeaderLine& h, bool seen_before) {
    if (seen_before) return Error("second format line");
    if (h.size != 3 || h.overflow) {
      return Error("format line needs an encoding and a version");
    }
    std::string_view encoding = h.tokens[1];
    if (encoding == "ascii") {
      header_.encoding = PlyEncoding::kAscii;
    } else if (encoding == "binary_little_endian") {
      header_.encoding = PlyEncoding::kBinaryLittleEndian;
    } else if (encoding == "binary_big_endian") {
      header_.encoding = PlyEncoding::kBinaryBigEndian;
    } else {
      return Error("unknown format " + Quoted(encoding));
    }
    if (h.tokens[2] != "1.0" && h.tokens[2] != "1") {
      return Error("unsupported PLY version " + Quoted(h.tokens[2]));
    }
    return Status::Ok();
  }

  Status ParseElement(const HeaderLine& h) {
    if (h.size != 3 || h.overflow)
      return Error("element needs a name and a count");
    uint64_t count = 0;
    if (!ParseUint64(h.tokens[2], &count)) {
      return Error("bad element count " + Quoted(h.tokens[2]));
    }
    PlyElement element;
    element.name = std::string(h.tokens[1]);
    element.count = count;
    element.line = lines_.number();
    header_.elements.push_back(std::move(element));
    return Status::Ok();
  }

  Status ParseProperty(const HeaderLine& h) {
    if (header_.elements.empty()) return Error("property before any element");
    PlyProperty property;
    if (h.size >= 2 && h.tokens[1] == "list") {
      if (h.size != 5 || h.overflow) {
        return Error(
            "list property needs a count type, an item type and a name");
      }
      std::optional<PlyScalar> count_type = ScalarFromName(h.tokens[2]);
      std::optional<PlyScalar> item_type = ScalarFromName(h.tokens[3]);
      if (!count_type)
        return Error("unknown property type " + Quoted(h.tokens[2]));
      if (!item_type)
        return Error("unknown property type " + Quoted(h.tokens[3]));
      if (!IsIntegerScalar(*count_type)) {
        return Error("list count type " + Quoted(h.tokens[2]) +
                     " is not an integer type");
      }
      property.is_list = true;
      property.count_type = *count_type;
      property.type = *item_type;
      property.name = std::string(h.tokens[4]);
    } else {
      if (h.size != 3 || h.overflow)
        return Error("property needs a type and a name");
      std::optional<PlyScalar> type = ScalarFromName(h.tokens[1]);
      if (!type) return Error("unknown property type " + Quoted(h.tokens[1]));
      property.type = *type;
      property.name = std::string(h.tokens[2]);
    }
    header_.elements.back().properties.push_back(std::move(property));
    return Status::Ok();
  }

  Status ElementError(const PlyElement& e, const std::string& what) const {
    return MeshParseError(name_, LineWhere(e.line),
                          "element " + e.name + ": " + what);
  }

  // Finds the vertex and face elements and checks what the readers rely on.
  Status FindMesh() {
    PlyMeshLayout& layout = header_.layout;
    for (size_t i = 0; i < header_.elements.size(); ++i) {
      const PlyElement& e = header_.elements[i];
      if (e.name != "vertex" && e.name != "face") continue;
      size_t& slot =
          e.name == "vertex" ? layout.vertex_element : layout.face_element;
      if (slot != PlyMeshLayout::kNone)
        return ElementError(e, "declared twice");
      slot = i;
    }
    if (layout.vertex_element != PlyMeshLayout::kNone) {
      const PlyElement& v = header_.elements[layout.vertex_element];
      static constexpr std::array<std::string_view, 3> kAxes = {"x", "y", "z"};
      for (size_t p = 0; p < v.properties.size(); ++p) {
        for (size_t axis = 0; axis < 3; ++axis) {
          if (v.properties[p].name != kAxes[axis]) continue;
          if (v.properties[p].is_list) {
            return ElementError(
                v, "property " + v.properties[p].name + " is a list");
          }
          layout.xyz[axis] = p;
        }
      }
      static constexpr std::array<std::string_view, 4> kChannels = {
          "red", "green", "blue", "alpha"};
      for (size_t p = 0; p < v.properties.size(); ++p) {
        if (v.properties[p].is_list) continue;
        std::string_view n = v.properties[p].name;
        if (n.starts_with("diffuse_")) n.remove_prefix(8);
        for (size_t c = 0; c < 4; ++c) {
          if (n == kChannels[c] && layout.rgba[c] == PlyMeshLayout::kNone) {
            layout.rgba[c] = p;
          }
        }
      }
      for (size_t axis = 0; axis < 3; ++axis) {
        if (layout.xyz[axis] == PlyMeshLayout::kNone) {
          return ElementError(v, "no property " + std::string(kAxes[axis]));
        }
      }
      if (v.count > kMaxVertices) {
        return ElementError(
            v, std::to_string(v.count) +
                   " vertices are more than 32-bit indices address");
      }
      layout.vertex_count = v.count;
    }
    if (layout.face_element != PlyMeshLayout::kNone) {
      const PlyElement& f = header_.elements[layout.face_element];
      for (size_t p = 0; p < f.properties.size(); ++p) {
        const std::string& n = f.properties[p].name;
        if (n == "vertex_indices" || n == "vertex_index") layout.indices = p;
      }
      if (layout.indices == PlyMeshLayout::kNone) {
        return ElementError(f, "no vertex_indices list");
      }
      const PlyProperty& indices = f.properties[layout.indices];
      if (!indices.is_list)
        return ElementError(f, indices.name + " is not a list");
      if (!IsIntegerScalar(indices.type)) {
        return ElementError(f, indices.name + " items are " +
                                   PlyScalarName(indices.type) +
                                   ", not integers");
      }
      if (f.count > 0 && layout.vertex_element == PlyMeshLayout::kNone) {
        return ElementError(f, "faces but no vertex element");
      }
    }
    return Status::Ok();
  }

  std::string_view name_;
  LineSplitter lines_;
  PlyHeader header_;
};

}  // namespace

size_t PlyScalarSize(PlyScalar type) {
  switch (type) {
    case PlyScalar::kInt8:
    case PlyScalar::kUint8:
      return 1;
    case PlyScalar::kInt16:
    case PlyScalar::kUint16:
      return 2;
    case PlyScalar::kInt32:
    case PlyScalar::kUint32:
    case PlyScalar::kFloat32:
      return 4;
    case PlyScalar::kFloat64:
      return 8;
  }
  return 0;
}

const char* PlyScalarName(PlyScalar type) {
  switch (type) {
    case PlyScalar::kInt8:
      return "char";
    case PlyScalar::kUint8:
      return "uchar";
    case PlyScalar::kInt16:
      return "short";
    case PlyScalar::kUint16:
      return "ushort";
    case PlyScalar::kInt32:
      return "int";
    case PlyScalar::kUint32:
      return "uint";
    case PlyScalar::kFloat32:
      return "float";
    case PlyScalar::kFloat64:
      return "double";
  }
  return "?";
}

bool PlyElement::HasLists() const {
  for (const PlyProperty& p : properties) {
    if (p.is_list) return true;
  }
  return false;
}

size_t PlyElement::MinBinaryRecordSize() const {
  size_t size = 0;
  for (const PlyProperty& p : properties) {
    size += PlyScalarSize(p.is_list ? p.count_type : p.type);
  }
  return size;
}

float PlyColorChannel(double value, PlyScalar type) {
  double scale = 1.0;
  switch (type) {
    case PlyScalar::kInt8:
      scale = 127.0;
      break;
    case PlyScalar::kUint8:
      scale = 255.0;
      break;
    case PlyScalar::kInt16:
      scale = 32767.0;
      break;
    case PlyScalar::kUint16:
      scale = 65535.0;
      break;
    case PlyScalar::kInt32:
      scale = 2147483647.0;
      break;
    case PlyScalar::kUint32:
      scale = 4294967295.0;
      break;
    case PlyScalar::kFloat32:
    case PlyScalar::kFloat64:
      break;
  }
  const double v = value / scale;
  return static_cast<float>(v < 0.0 ? 0.0 : v > 1.0 ? 1.0 : v);
}

Result<PlyHeader> ParsePlyHeader(std::string_view bytes,
                                 std::string_view name) {
  return HeaderParser(bytes, name).Parse();
}

}  // namespace meshwave
