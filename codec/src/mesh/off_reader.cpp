// Geomview OFF reader: an optional [ST][C][N]OFF keyword, then the counts
// "V F [E]", V vertex lines and F face lines "n i0 ... i(n-1) [colour]".
// Records are one per line; '#' starts a comment; what follows x y z on a
// vertex line (normals, colours, texture coordinates) is ignored, as is a
// colour after a face's indices. Polygons are fan-triangulated.
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "core/byte_reader.h"
#include "mesh/mesh_readers.h"
#include "mesh/text_scanner.h"

namespace meshwave {
namespace {

enum class Keyword { kOff, kUnsupported, kNone };

Keyword ClassifyKeyword(std::string_view token) {
  std::string_view rest = token;
  if (rest.starts_with("ST")) rest.remove_prefix(2);
  if (rest.starts_with("C")) rest.remove_prefix(1);
  if (rest.starts_with("N")) rest.remove_prefix(1);
  if (rest.starts_with("4") || rest.starts_with("n")) {
    return rest.ends_with("OFF") ? Keyword::kUnsupported : Keyword::kNone;
  }
  return rest == "OFF" ? Keyword::kOff : Keyword::kNone;
}

class OffParser {
 public:
  OffParser(std::string_view bytes, std::string_view name)
      : name_(name), lines_(bytes) {}

  Result<TriMesh> Parse() {
    std::string_view line;
    if (!NextContentLine(&line)) return Error("empty file (no OFF header)");
    TokenSplitter tokens(line);
    std::string_view first;
    tokens.Next(&first);  // a content line has at least one token
    Keyword keyword = ClassifyKeyword(first);
    if (keyword == Keyword::kUnsupported) {
      return Error(Quoted(first) +
                   " (4D or n-dimensional OFF) is not supported");
    }
    if (keyword == Keyword::kNone) {
      uint64_t ignored = 0;
      if (!ParseUint64(first, &ignored)) {
        return Error("not an OFF file: " + Quoted(first) +
                     " is no OFF keyword");
      }
      tokens = TokenSplitter(line);  // the keyword is optional: counts follow
    } else {
      std::string_view rest = tokens.Rest();
      if (rest.starts_with("BINARY"))
        return Error("binary OFF is not supported");
      if (rest.empty()) {
        if (!NextContentLine(&line))
          return Error("file ends before the counts");
        tokens = TokenSplitter(line);
      }
    }
    MW_RETURN_IF_ERROR(ParseCounts(tokens));
    MW_RETURN_IF_ERROR(ReadVertices());
    MW_RETURN_IF_ERROR(ReadFaces());
    return std::move(mesh_);
  }

 private:
  Status Error(const std::string& what) const {
    return MeshParseError(name_, LineWhere(lines_.number()), what);
  }

  // The next line that holds something besides a comment, comment removed.
  bool NextContentLine(std::string_view* line) {
    while (lines_.Next(line)) {
      size_t hash = line->find('#');
      if (hash != std::string_view::npos) *line = line->substr(0, hash);
      if (!TokenSplitter(*line).Rest().empty()) return true;
    }
    return false;
  }

  Status ParseCounts(TokenSplitter& tokens) {
    std::string_view v_token, f_token;
    if (!tokens.Next(&v_token) || !tokens.Next(&f_token)) {
      return Error("expected the vertex and face counts");
    }
    if (!ParseUint64(v_token, &vertex_count_)) {
      return Error("bad vertex count " + Quoted(v_token));
    }
    if (!ParseUint64(f_token, &face_count_)) {
      return Error("bad face count " + Quoted(f_token));
    }
    if (vertex_count_ > kMaxVertices) {
      return Error(std::to_string(vertex_count_) +
                   " vertices are more than 32-bit indices address");
    }
    // A vertex line takes at least 6 bytes ("0 0 0\n"), any face line at
    // least 2 (valid ones 8, but a short or cut face deserves its own error);
    // the last line may lack its newline.
    std::optional<size_t> vertex_bytes = CheckedMul(vertex_count_, 6);
    std::optional<size_t> face_bytes = CheckedMul(face_count_, 2);
    size_t remaining = lines_.remaining();
    if (!vertex_bytes || !face_bytes || *vertex_bytes > remaining + 1 ||
        *face_bytes > remaining + 1 - *vertex_bytes) {
      return Error(std::to_string(vertex_count_) + " vertices and " +
                   std::to_string(face_count_) + " faces cannot fit in the " +
                   std::to_string(remaining) + " bytes that remain");
    }
    return Status::Ok();
  }

  Status ReadVertices() {
    mesh_.positions.reserve(static_cast<size_t>(vertex_count_));  // checked
    for (uint64_t v = 0; v < vertex_count_; ++v) {
      std::string_view line;
      if (!NextContentLine(&line)) {
        return Error("file ends after " + std::to_string(v) + " of " +
                     std::to_string(vertex_count_) + " vertices");
      }
      TokenSplitter tokens(line);
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
      mesh_.positions.push_back(position);
    }
    return Status::Ok();
  }

  Status ReadFaces() {
    // Reserve only as many triangles as the rest of the file can hold.
    mesh_.faces.reserve(std::min<size_t>(face_count_, lines_.remaining() / 8));
    for (uint64_t f = 0; f < face_count_; ++f) {
      std::string_view line;
      if (!NextContentLine(&line)) {
        return Error("file ends after " + std::to_string(f) + " of " +
                     std::to_string(face_count_) + " faces");
      }
      MW_RETURN_IF_ERROR(ReadFace(line));
    }
    return Status::Ok();
  }

  Status ReadFace(std::string_view line) {
    TokenSplitter tokens(line);
    std::string_view token;
    int64_t n = 0;
    tokens.Next(&token);  // a content line has at least one token
    if (!ParseInt64(token, &n))
      return Error("bad corner count " + Quoted(token));
    if (n < 3) {
      return Error("face with " + std::to_string(n) +
                   " corners (at least 3 needed)");
    }
    uint32_t corners[3] = {0, 0, 0};
    for (int64_t k = 0; k < n; ++k) {  // each step consumes a token or stops
      if (!tokens.Next(&token)) {
        return Error("face has " + std::to_string(k) + " of its " +
                     std::to_string(n) + " indices");
      }
      int64_t index = 0;
      if (!ParseInt64(token, &index))
        return Error("bad vertex index " + Quoted(token));
      if (index < 0 || static_cast<uint64_t>(index) >= vertex_count_) {
        return Error("vertex index " + std::to_string(index) +
                     " out of range (" + std::to_string(vertex_count_) +
                     " vertices)");
      }
      corners[k < 2 ? k : 2] = static_cast<uint32_t>(index);
      if (k >= 2) {
        mesh_.faces.push_back({corners[0], corners[1], corners[2]});
        corners[1] = corners[2];  // fan around the first corner
      }
    }
    return Status::Ok();
  }

  std::string_view name_;
  LineSplitter lines_;
  uint64_t vertex_count_ = 0;
  uint64_t face_count_ = 0;
  TriMesh mesh_;
};

}  // namespace

Result<TriMesh> ParseOff(std::string_view bytes, std::string_view name) {
  return OffParser(bytes, name).Parse();
}

}  // namespace meshwave
