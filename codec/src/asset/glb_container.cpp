#include "asset/glb_container.h"

#include <bit>
#include <cstdint>
#include <string>

#include "core/byte_reader.h"

namespace meshwave {
namespace {

constexpr uint32_t kGlbMagic = 0x46546C67;   // "glTF"
constexpr uint32_t kChunkJson = 0x4E4F534A;  // "JSON"
constexpr uint32_t kChunkBin = 0x004E4942;   // "BIN\0"

Status GlbError(std::string_view name, const std::string& what) {
  return ParseError(std::string(name) + ": " + what);
}

}  // namespace

bool LooksLikeGlb(std::string_view bytes) { return bytes.starts_with("glTF"); }

Result<GlbChunks> ParseGlb(std::string_view bytes, std::string_view name) {
  ByteReader reader(bytes);
  uint32_t magic = 0;
  uint32_t version = 0;
  uint32_t length = 0;
  if (!reader.Read(std::endian::little, &magic) ||
      !reader.Read(std::endian::little, &version) ||
      !reader.Read(std::endian::little, &length)) {
    return GlbError(name, "GLB header truncated (" +
                              std::to_string(bytes.size()) +
                              " bytes, the header alone takes 12)");
  }
  if (magic != kGlbMagic)
    return GlbError(name, "not a GLB file (no \"glTF\" magic)");
  if (version != 2) {
    return Status(StatusCode::kUnsupported,
                  std::string(name) + ": GLB version " +
                      std::to_string(version) +
                      " (only glTF 2.0 is supported)");
  }
  if (length > bytes.size()) {
    return GlbError(name, "truncated: the GLB header declares " +
                              std::to_string(length) + " bytes, the file has " +
                              std::to_string(bytes.size()));
  }
  if (length < bytes.size()) {
    return GlbError(name, std::to_string(bytes.size() - length) +
                              " bytes after the " + std::to_string(length) +
                              " the GLB header declares");
  }
  GlbChunks chunks;
  bool have_json = false;
  while (!reader.empty()) {
    uint32_t chunk_length = 0;
    uint32_t chunk_type = 0;
    const size_t at = reader.position();
    if (!reader.Read(std::endian::little, &chunk_length) ||
        !reader.Read(std::endian::little, &chunk_type)) {
      return GlbError(name, "GLB chunk header at byte " + std::to_string(at) +
                                " truncated");
    }
    std::string_view data;
    if (!reader.ReadBytes(chunk_length, &data)) {
      return GlbError(name, "GLB chunk at byte " + std::to_string(at) +
                                " declares " + std::to_string(chunk_length) +
                                " bytes, only " +
                                std::to_string(reader.remaining()) + " remain");
    }
    if (!have_json) {
      if (chunk_type != kChunkJson) {
        return GlbError(name, "the first GLB chunk is not JSON");
      }
      chunks.json = data;
      have_json = true;
    } else if (chunk_type == kChunkBin && !chunks.has_bin) {
      chunks.bin = data;
      chunks.has_bin = true;
    } else if (chunk_type == kChunkJson || chunk_type == kChunkBin) {
      return GlbError(name, "a second JSON or BIN chunk");
    }
    // Chunks of other types are skipped (glTF 2.0: "Client implementations
    // must ignore chunks with unknown types").
  }
  if (!have_json) return GlbError(name, "GLB without a JSON chunk");
  return chunks;
}

}  // namespace meshwave
