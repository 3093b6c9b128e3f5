// Encoding a semi-regular mesh into an embedded 3xC (or SIM) bitstream:
// wavelet transform, deadzone quantisation, bitplane coding into packets.
#ifndef MESHWAVE_ENCODER_H_
#define MESHWAVE_ENCODER_H_

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "meshwave/semiregular.h"
#include "meshwave/status.h"
#include "meshwave/stream_header.h"
#include "meshwave/texture.h"
#include "meshwave/wavelet.h"

namespace meshwave {

enum class CoderKind { k3xC, kSim };
Result<CoderKind> ParseCoderKind(const std::string& name);  // "3xc", "sim"
const char* CoderKindName(CoderKind coder);

struct EncodeOptions {
  TransformSettings transform;
  CoderKind coder = CoderKind::k3xC;
  // Finest step = bounding-box diagonal * 2^-precision; 16 gives a complete
  // stream well above 90 dB PSNR.
  int precision = 16;
  // Cells of at most this many coefficients are coded one by one. 32 beat
  // 2 and 8 at every rate on the four meshes of docs/RD_RESULTS.md.
  uint32_t octree_leaf_size = 32;
  // Precincts (docs/FORMAT.md 2.2): base faces grouped into runs of at
  // least this many coefficients per subband, each coded on its own so that
  // a region can be sent first; 0: one precinct per subband. What they cost
  // grows with their number (fresh contexts, borders): 2,048 cost up to
  // 0.5 dB at equal bytes at high rates, 4,096 at most 0.26 dB
  // (docs/RD_RESULTS.md, "Precincts").
  uint32_t precinct_coefficients = 4096;
  // A packet is split into one codeword per precinct where its precincts
  // would average at least this many bytes: below, the parts' lengths and
  // flushes cost more than sending the region's share alone saves.
  uint32_t split_bytes_per_precinct = 48;
  // With local frames, the tangential components' step is this many times
  // the normal one's, and their error counts 1 / scale^2 in the packet
  // order: a vertex that slides along the surface barely moves the surface,
  // which is what a user's distance to the original measures. 8 beat 1, 2,
  // 4 and 16 at mid and high rates on the shared meshes (docs/RD_RESULTS.md,
  // "Tangential step"). 1 quantises every component alike.
  double tangent_step_scale = 8;
  // The base mesh's positions travel in the header on a grid 2^R times
  // coarser than their own, and R packets refine them a bit per coordinate
  // at a time (docs/FORMAT.md 3.3), so that a low-rate prefix does not pay
  // for the base's low bits. -1: the largest R that costs the complete
  // stream at most 2 % more base bytes (ChooseBaseRefinementPlanes); 0: the
  // whole base in the header. PGC always sends the whole base.
  int base_refinement_planes = -1;
  int deadzone = 0;  // xi0 code (quant/deadzone_quantizer.h): 0 = SAQ
  // `--quantizer auto` (Satti et al. 2011): each (subband, component) gets the
  // deadzone its fitted Laplacian mixture calls for (sigma2/sigma1: UEQ
  // below 120, z = 1.5 to 290, SAQ to 600, z = 2.5 above); `deadzone` is
  // then only the fallback for tiny subbands. 3xC and SIM only: the PGC
  // baseline keeps one deadzone.
  bool auto_deadzone = false;
  // SAWT (transform.predictor == kSawt, Denis et al. 2010a): octree cells split while
  // they hold >= sawt_alpha vertices, and the Lagrangian of each filter
  // choice weighs its index bits by lambda = sawt_lambda_scale * step^2,
  // step being the finest step above (docs/ANALYSIS.md for the tuning).
  uint32_t sawt_alpha = 400;
  double sawt_lambda_scale = 64.0;
  // The colour channel's finest step is 2^-color_precision (colours in
  // [0, 1]): 10 puts the complete stream's colours well inside an 8-bit
  // input's steps (1/255).
  int color_precision = 10;
  // The weight of the colour channel's distortion against the geometry's
  // in the rd order (docs/FORMAT.md 7), both normalised to their peaks.
  float color_rd_weight = 1;
  // The weight of the texture's distortion (peak 1) against the geometry's
  // (over the diagonal²) in the packet orders (docs/FORMAT.md 7). A
  // geometry error of e diagonals moves a picture D pixels across by e·D
  // pixels, whose cost grows with the picture's gradients: 1e-4 is
  // 1/(D²·G) for D of some 600 pixels and G, the mean squared gradient, of
  // 0.03² a pixel. Measured on spot's rendered pixels against the
  // original's (docs/CODEC.md, "Texture against geometry"): 1e-4 is within
  // 1.3 dB of the best weight at every budget; 1 sent all of the texture
  // before the geometry's refinement, 2-8 dB worse.
  float texture_rd_weight = 1e-4f;
  // The original layer's positions packets after its coarse one
  // (docs/FORMAT.md 2.5); -1: as many as keep the coarse positions closer
  // to the original than the remesh is.
  int original_refinement_planes = -1;
  std::string name;
  // Threads for quantising and coding (subbands on workers, the largest
  // first); 0: the machine's cores. The stream does not depend on it.
  int threads = 0;
};

// The complete stream: a header whose packet index lists every packet, and
// the packets' payloads in the same (canonical) order. The header is as a
// decoder reads it back from the bytes the encoder wrote (with protobuf):
// its bytes_without_present are the stream's header bytes.
struct EncodedStream {
  StreamHeader header;
  std::vector<std::string> packets;
  // The encoded mesh as the stream numbers it: the encoder reorders the base
  // mesh so that it codes compactly, and a decoder returns vertices in this
  // order. Compare decoded meshes with these positions.
  SemiRegularMesh mesh;
  // SAWT only: how many coded (level, region) choices took each of the
  // filters f1..f6, and the number of regions.
  std::vector<uint32_t> sawt_filter_usage;
  uint32_t sawt_regions = 0;
  // The encoded colours (linear RGB) in the order of `mesh`; empty without
  // a colour channel.
  std::vector<Vec3> colors;
};

// What a mesh carries besides its geometry: per vertex of its finest level
// in its vertex order (each empty when absent), and its texture baked into
// the atlas of its base faces (format version 9): base face f of the mesh
// given to EncodeMesh owns triangle f of the atlas, corners in order (the
// stream reorders the base; its header says where each face went).
struct VertexAttributes {
  std::vector<Vec3> colors;  // linear RGB in [0, 1]: the colour channel
  std::optional<BakedTexture> texture;
  // The user's mesh as read, when the stream is to end in it (format
  // version 10, docs/FORMAT.md 2.5): its connectivity over its own vertex
  // ids and its positions at EncodeOptions::precision. Not owned.
  const TriMesh* original = nullptr;
  // The remesh's symmetric surface PSNR against `original` (peak: its
  // bounding-box diagonal; 0: unknown or exact): the layer's coarse
  // positions err less (EncodeOptions::original_refinement_planes).
  double original_remesh_psnr_db = 0;
};

Result<EncodedStream> EncodeMesh(const SemiRegularMesh& mesh,
                                 const EncodeOptions& options);
// With a channel per attribute present (format version 8), the
// texture's maps as packets (version 9) and the original layer (version 10). kInvalidArgument when an
// attribute does not have one finite value per vertex, or the texture does
// not fit the mesh (stream/texture_encoder.h says what is checked).
Result<EncodedStream> EncodeMesh(const SemiRegularMesh& mesh, const EncodeOptions& options,
                                 const VertexAttributes& attributes);

// The .mwv container (meshwave/container.h) holding the packets `ids`.
std::string SerializeContainer(const EncodedStream& stream,
                               std::span<const uint32_t> ids);
// All packets in canonical order.
std::string SerializeFullContainer(const EncodedStream& stream);

}  // namespace meshwave

#endif  // MESHWAVE_ENCODER_H_
