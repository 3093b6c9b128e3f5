// Wavefront OBJ reader: `v` and `f` lines; polygons fan-triangulated;
// indices 1-based, negative ones relative to the vertices read so far;
// `v/vt/vn` corner forms accepted with texture and normal parts ignored.
// Other statements (vt, vn, g, o, s, usemtl, mtllib, l, ...) are skipped.
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "mesh/mesh_readers.h"
#include "mesh/text_scanner.h"

namespace meshwave {
namespace {

class ObjParser {
 public:
  ObjParser(std::string_view bytes, std::string_view name)
      : name_(name), lines_(bytes) {}

  Result<TriMesh> Parse() {
    std::string_view line;
    while (NextStatementLine(lines_, &line)) {
      TokenSplitter tokens(line);
      std::string_view keyword;
      if (!tokens.Next(&keyword)) continue;
      if (keyword == "v") {
        MW_RETURN_IF_ERROR(ParseVertex(tokens));
      } else if (keyword == "f") {
        MW_RETURN_IF_ERROR(ParseFace(tokens));
      }
    }
    // Forward references are rare but legal in practice; check them now
    // that every vertex is known.
    for (const ForwardReference& ref : forward_references_) {
      if (ref.index >= mesh_.positions.size()) {
        return MeshParseError(name_, LineWhere(ref.line),
                              "vertex index " + std::to_string(ref.index + 1) +
                                  " out of range (" +
                                  std::to_string(mesh_.positions.size()) +
                                  " vertices)");
      }
    }
    return std::move(mesh_);
  }

 private:
  struct ForwardReference {
    size_t line;
    uint64_t index;  // 0-based
  };

  Status Error(const std::string& what) const {
    return MeshParseError(name_, LineWhere(lines_.number()), what);
  }

  Status ParseVertex(TokenSplitter& tokens) {
    if (mesh_.positions.size() >= kMaxVertices) {
      return Error("more vertices than 32-bit indices address");
    }
    Vec3 position;
    for (int axis = 0; axis < 3; ++axis) {
      std::string_view token;
      if (!tokens.Next(&token)) return Error("vertex needs x, y and z");
      if (!ParseDouble(token, &position[axis])) {
        return Error("bad number " + Quoted(token));
      }
      if (!std::isfinite(position[axis])) {
        return Error("coordinate " + Quoted(token) + " is NaN or infinite");
      }
    }
    mesh_.positions.push_back(position);  // a w or a colour may follow
    return Status::Ok();
  }

  // Resolves one corner ("7", "7/2", "7//3", "-1/2/3") to a 0-based index.
  Status ParseCorner(std::string_view token, uint32_t* index) {
    std::string_view number = token.substr(0, token.find('/'));
    int64_t value = 0;
    if (!ParseInt64(number, &value))
      return Error("bad vertex index " + Quoted(token));
    const int64_t count = static_cast<int64_t>(mesh_.positions.size());
    if (value == 0) return Error("vertex index 0 (OBJ indices start at 1)");
    int64_t resolved = value > 0 ? value - 1 : count + value;
    if (resolved < 0 || static_cast<uint64_t>(resolved) >= kMaxVertices) {
      return Error("vertex index " + std::to_string(value) + " out of range (" +
                   std::to_string(count) + " vertices so far)");
    }
    if (resolved >= count) {
      forward_references_.push_back(
          {lines_.number(), static_cast<uint64_t>(resolved)});
    }
    *index = static_cast<uint32_t>(resolved);
    return Status::Ok();
  }

  Status ParseFace(TokenSplitter& tokens) {
    uint32_t corners[3] = {0, 0, 0};
    size_t n = 0;
    std::string_view token;
    while (tokens.Next(&token)) {
      uint32_t index = 0;
      MW_RETURN_IF_ERROR(ParseCorner(token, &index));
      corners[n < 2 ? n : 2] = index;
      if (n >= 2) {
        mesh_.faces.push_back({corners[0], corners[1], corners[2]});
        corners[1] = corners[2];  // fan around the first corner
      }
      ++n;
    }
    if (n < 3) {
      return Error("face with " + std::to_string(n) +
                   " corners (at least 3 needed)");
    }
    return Status::Ok();
  }

  std::string_view name_;
  LineSplitter lines_;
  TriMesh mesh_;
  std::vector<ForwardReference> forward_references_;
};

}  // namespace

Result<TriMesh> ParseObj(std::string_view bytes, std::string_view name) {
  return ObjParser(bytes, name).Parse();
}

}  // namespace meshwave
