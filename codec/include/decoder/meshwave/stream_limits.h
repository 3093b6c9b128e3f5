// Limits of the .mwv stream (docs/FORMAT.md), each written once: the
// encoder, the decoders, the server, the client and the CLI read them here.
#ifndef MESHWAVE_STREAM_LIMITS_H_
#define MESHWAVE_STREAM_LIMITS_H_

#include <cstdint>

namespace meshwave {

// Subdivision levels J of a stream: 12 levels of a one-triangle base mesh
// are already 4^12 = 16.8 million faces.
inline constexpr int kMaxStreamLevels = 12;

// Bytes of a stream header (the container preamble's length field): large
// enough for any header the encoder writes, small enough that a hostile
// stream cannot make a reader buffer without bound.
inline constexpr uint32_t kMaxHeaderBytes = 64u << 20;

// Textures (docs/FORMAT.md 2.4): at most one map per role, each of at most
// kMaxTextureLevels levels (8 levels of a 16384-texel atlas go down to 128
// texels), each level one whole image of one of these types (WebP from
// format version 11).
inline constexpr uint32_t kMaxTextureMaps = 5;
inline constexpr uint32_t kMaxTextureLevels = 8;
inline constexpr const char* kTextureMimeTypes[] = {"image/jpeg", "image/png", "image/webp"};

// The original layer (docs/FORMAT.md 2.5): the user's mesh, at most this
// many vertices and faces (a decoder may accept fewer faces:
// DecoderOptions::max_faces).
inline constexpr uint32_t kMaxOriginalVertices = 1u << 28;
inline constexpr uint64_t kMaxOriginalFaces = uint64_t{1} << 29;

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_LIMITS_H_
