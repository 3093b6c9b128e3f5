// The per-format parsers behind ParseMesh, and what they share. Each one
// returns a ParseError "<name>: <where>: <what>" for malformed input, where
// <where> is a line ("line 12") or an element ("face 17").
#ifndef MESHWAVE_MESH_MESH_READERS_H_
#define MESHWAVE_MESH_MESH_READERS_H_

#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <utility>

#include "meshwave/mesh.h"
#include "meshwave/status.h"

namespace meshwave {

Result<TriMesh> ParsePly(std::string_view bytes, std::string_view name);
Result<TriMesh> ParseObj(std::string_view bytes, std::string_view name);
Result<TriMesh> ParseOff(std::string_view bytes, std::string_view name);

// "<name>: <where>: <what>" as a ParseError.
inline Status MeshParseError(std::string_view name, std::string_view where,
                             std::string_view what) {
  std::string message(name);
  message += ": ";
  message += where;
  message += ": ";
  message += what;
  return ParseError(std::move(message));
}

inline std::string LineWhere(size_t line) {
  return "line " + std::to_string(line);
}

// Face indices are uint32_t, so no mesh may have more vertices than this.
inline constexpr uint64_t kMaxVertices = std::numeric_limits<uint32_t>::max();

}  // namespace meshwave

#endif  // MESHWAVE_MESH_MESH_READERS_H_
