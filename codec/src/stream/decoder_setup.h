// What both decoders of the codec, ProgressiveDecoder and the PGC
// measurement decoder (pgc/), check in a header and build from it before
// any packet: one home for those checks and that setup.
#ifndef MESHWAVE_STREAM_DECODER_SETUP_H_
#define MESHWAVE_STREAM_DECODER_SETUP_H_

#include <cstdint>
#include <memory>

#include "meshwave/semiregular.h"
#include "meshwave/status.h"
#include "meshwave/stream_header.h"
#include "meshwave/wavelet.h"
#include "stream/base_mesh_decoder.h"

namespace meshwave {

// A format version this build reads (CheckFormatVersion) and at most
// kMaxStreamLevels levels.
Status ValidateVersionAndLevels(const StreamHeader& h);

// One quantizer per (subband, component), each with a finite positive step,
// a known deadzone code and a top bitplane in [-1, kMaxBitplane].
Status ValidateQuantizers(const StreamHeader& h);

// At most kMaxChannels channels, each of a known kind (one of each), with a
// quantizer per (subband, component) as the geometry's, a finite positive
// base step and rd weight, and room for 3 base values per base vertex.
Status ValidateChannels(const StreamHeader& h);

// A texture (format version 9, docs/FORMAT.md 2.4), when the header has
// one: 1 to kMaxTextureMaps maps of distinct known roles, each of 1 to
// kMaxTextureLevels levels of a known image type, the level sizes the
// atlas's halved, each level naming its packet in the index order; an
// atlas AtlasLayout accepts for the base faces, face_triangles empty or a
// permutation of them with a rotation each; finite material scalars and a
// finite positive rd weight.
Status ValidateTexture(const StreamHeader& h);

// The original layer (format version 10, docs/FORMAT.md 2.5), when the
// header has one: 1 to kMaxOriginalVertices vertices, at most
// kMaxOriginalFaces faces, a
// grid of 3 finite origin coordinates and a finite positive step, an
// extent within the positions code's range, and at most
// kMaxOriginalRefinementPlanes refinement planes.
Status ValidateOriginal(const StreamHeader& h);

// Decodes the base mesh (at most `max_base_vertices`) into `base`, builds
// `hierarchy` and checks the header's vertex and face counts and bounding
// box against it; returns the header's transform settings (with the SAWT
// choices, when it has them). ParseError on anything that does not fit.
Result<TransformSettings> SetUpHierarchy(const StreamHeader& header, uint32_t max_base_vertices,
                                         DecodedBase& base,
                                         std::shared_ptr<const SemiRegularHierarchy>& hierarchy);

// SetUpHierarchy, then `transform`, the inverse transform of its settings.
Status SetUpDecoder(const StreamHeader& header, uint32_t max_base_vertices, DecodedBase& base,
                    std::shared_ptr<const SemiRegularHierarchy>& hierarchy,
                    std::unique_ptr<WaveletTransform>& transform);

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_DECODER_SETUP_H_
