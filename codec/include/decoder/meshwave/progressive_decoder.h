// ProgressiveDecoder: takes a stream header, then packets one at a time in
// any order that respects their dependencies, and gives the current mesh at
// any time. The same object serves a file, an HTTP response and a WebSocket
// session; it does no I/O. Safe on untrusted input: every header field and
// every packet is checked (bounds, CRC-16 check, dependencies) before use.
#ifndef MESHWAVE_PROGRESSIVE_DECODER_H_
#define MESHWAVE_PROGRESSIVE_DECODER_H_

#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "meshwave/held_units.h"
#include "meshwave/mesh.h"
#include "meshwave/status.h"
#include "meshwave/stream_header.h"
#include "meshwave/texture.h"

namespace meshwave {

struct DecoderOptions {
  // Reconstruction point inside a quantiser cell, as a fraction of the cell
  // (0.5: midpoint). Does not affect parsing.
  double gamma = 0.5;
  uint32_t max_base_vertices = 1u << 24;
  // Faces of the finest level. A header is refused before anything is
  // allocated when it claims more: a client bounds its memory with it (a
  // small header can claim 12 levels), the fuzzers their time per input.
  // The original layer's faces and vertices are bounded by it too.
  uint64_t max_faces = uint64_t{1} << 27;
  // Create builds what the base mesh and the first mesh need and returns;
  // the rest of the set-up (each subband's octree and coding state, which
  // its packets need, and each finer level's inverse transform, which its
  // meshes need) is built on first use, only as far as used. When `threads`
  // is 2 or more, one more thread also builds it ahead of use, finest last,
  // and gives up what is left when the decoder is destroyed. 0: two where
  // the machine has two cores or more. A WebAssembly build without threads
  // always uses one. Results do not depend on it.
  int threads = 0;
};

class ProgressiveDecoder {
 public:
  static Result<std::unique_ptr<ProgressiveDecoder>> Create(
      const StreamHeader& header, const DecoderOptions& options = {});
  ~ProgressiveDecoder();

  // The header given to Create, `present` cleared.
  const StreamHeader& header() const;
  size_t packet_count() const;
  bool HasPacket(uint32_t id) const;
  // True when every packet `id` depends on has been added.
  bool DependenciesMet(uint32_t id) const;
  // The units added so far, with the rules of what each needs
  // (meshwave/held_units.h): what AddPacket and AddPacketPart check.
  const HeldUnits& held() const;

  // Checks and decodes one packet. Errors: unknown id, packet already added,
  // missing dependency (kInvalidArgument: nothing changed, the decoder stays
  // usable), CRC or length mismatch (kParseError, nothing changed), and a
  // payload that passed the CRC but does not decode (kParseError; the
  // decoder is then unusable, as its state is half-updated).
  Status AddPacket(uint32_t id, std::string_view payload);

  // Split packets (docs/FORMAT.md 2.2) also travel precinct by precinct:
  // how many parts packet `id` has (0: not split), whether part `part` is
  // held (a whole packet holds all of its parts), and whether the parts it
  // depends on are: the same precinct's part (or the whole packet) one
  // bitplane up, and with 3xC the parent precinct's at the same bitplane.
  uint32_t PartCount(uint32_t id) const;
  bool HasPart(uint32_t id, uint32_t part) const;
  bool PartDependenciesMet(uint32_t id, uint32_t part) const;
  // Decodes one part of a split packet. Errors as AddPacket's, except that
  // a part has no check of its own (the index checks whole packets): the
  // transport's integrity is its check. AddPacket on a packet some of whose
  // parts are held decodes only the others.
  Status AddPacketPart(uint32_t id, uint32_t part, std::string_view payload);

  // Forgets every packet: the decoder is as Create left it (the base mesh
  // only), usable again after a corrupt packet broke it, without rebuilding
  // the hierarchy and transform (most of Create's time).
  void Reset();

  // Waits for (or builds) the rest of the set-up (DecoderOptions::threads),
  // which AddPacket and a fine Mesh() otherwise do when they first need
  // it: for callers that want that time out of their first packet.
  void CompleteSetUp() const;

  size_t packets_decoded() const;
  uint64_t payload_bytes_decoded() const;
  // The finest level whose subbands have all received at least one packet
  // (0: only the base mesh).
  int CompleteLevels() const;
  // The finest level at which a packet held gave some detail a nonzero
  // value (0: the base mesh alone). Every finer level holds zero details:
  // its mesh would be this one subdivided, four times the faces a level
  // and none of the received detail, so Mesh(DetailLevels()) is the
  // smallest mesh that carries everything received.
  int DetailLevels() const;
  // Estimated PSNR (peak = bounding-box diagonal) against the encoded mesh,
  // from the index's distortion figures for the packets held: a vertex
  // error whose part along the surface counts 1 / s^2 (s the tangential
  // step scale, docs/CODEC.md), so close to the error off the surface. The
  // symmetric surface PSNR (`meshwave compare`) is usually 0 to 5 dB higher:
  // between vertices the surface interpolates their errors.
  double EstimatedPsnr() const;

  // The mesh at level max_level (-1: the finest level, J). AddPacket only
  // updates the coefficients; each call here reconstructs the mesh from them
  // (dequantisation and the inverse transform: a few ms per 100 k vertices),
  // so call it when a mesh is needed, not after every packet by default.
  std::vector<Vec3> Positions(int max_level = -1) const;
  // The faces of level max_level (-1 or beyond J: J), which need no packet.
  std::vector<Face> Faces(int max_level = -1) const;
  TriMesh Mesh(int max_level = -1) const;

  // Whether the stream has the original layer (format version 10,
  // docs/FORMAT.md 2.5): the user's own mesh after the semi-regular
  // stream. OriginalReady: enough of it is held to give that mesh (its
  // connectivity and coarse positions); EstimatedPsnr is then the
  // original's.
  bool HasOriginal() const;
  bool OriginalReady() const;
  // The user's mesh: its faces over its own vertex ids (face i's corners
  // possibly rotated, faces in another order), each position the middle
  // of the grid cell the packets held leave it in: within half a grid step
  // per coordinate once every positions packet is held. Empty before
  // OriginalReady.
  TriMesh OriginalMesh() const;

  // Whether the stream has a colour channel (format version 8).
  bool HasColors() const;
  // Per vertex of Positions(max_level), its colour from the packets added
  // so far: linear RGB, each component clamped to [0, 1]. Empty when the
  // stream has no colour channel. Costs about what Positions does.
  std::vector<Vec3> Colors(int max_level = -1) const;

  // Whether the stream has a texture (format version 9, docs/FORMAT.md
  // 2.4), and its description: atlas, material scalars, and per map its
  // role, image type and level sizes (no maps without a texture).
  bool HasTexture() const;
  const TextureInfo& texture() const;
  // Per face corner of Faces(max_level), its texture coordinates from the
  // atlas (they never travel): 6 floats a face, u0 v0 u1 v1 u2 v2, glTF's
  // convention (v down the image). Empty without a texture.
  std::vector<float> TextureCoordinates(int max_level = -1) const;
  // The finest level of map `map` (an index into texture().maps) held, or
  // nullopt when none of its levels is (or there is no such map).
  std::optional<TextureImage> BestTextureLevel(size_t map) const;

 private:
  struct Impl;
  explicit ProgressiveDecoder(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace meshwave

#endif  // MESHWAVE_PROGRESSIVE_DECODER_H_
