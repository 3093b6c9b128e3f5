// The texture of a stream (format version 9, docs/FORMAT.md 2.4): checks a
// baked texture against the mesh, and lays out its header field, its
// packets (one whole image per level) and their distortion figures.
#ifndef MESHWAVE_STREAM_TEXTURE_ENCODER_H_
#define MESHWAVE_STREAM_TEXTURE_ENCODER_H_

#include <cstdint>
#include <string>
#include <vector>

#include "meshwave/encoder.h"
#include "meshwave/status.h"
#include "meshwave/texture.h"
#include "stream.pb.h"
#include "meshwave/semiregular.h"

namespace meshwave {

struct EncodedTexture {
  proto::Texture header;             // level packet ids from first_packet on
  std::vector<std::string> packets;  // map by map, coarsest level first
  // Per map, its chain's start, and per packet its reduction, in the units
  // of the rd order's channels: squared error (peak 1) summed over the
  // finest level's vertices (FORMAT.md 7).
  std::vector<double> chain_start;
  std::vector<double> reduction;
};

// kInvalidArgument, naming what is wrong, unless `texture` has 1 to
// kMaxTextureMaps maps of distinct roles, each of 1 to kMaxTextureLevels
// levels of its image type (image/jpeg or image/png) whose headers declare
// the atlas's size halved per level below the last; an atlas AtlasLayout
// accepts for the input's base faces; finite material scalars and a
// finite positive options.texture_rd_weight. `input` is the mesh the
// texture was baked on (its base faces own the atlas's triangles);
// `stream` the same mesh in the stream's order, input_vertex[v] the input's
// index of its vertex v (PreparedStream).
Result<EncodedTexture> EncodeTexture(const BakedTexture& texture, const SemiRegularMesh& input,
                                     const SemiRegularMesh& stream,
                                     const std::vector<uint32_t>& input_vertex,
                                     uint32_t first_packet, const EncodeOptions& options);

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_TEXTURE_ENCODER_H_
