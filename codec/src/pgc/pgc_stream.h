// The PGC baseline (Khodakovsky et al. 2000) as a whole codec: the same
// transform, base mesh coding, quantisers (per (subband, component), steps
// step0 / sqrt(G_j)) and arithmetic coder as EncodeMesh, but the bitplanes
// coded by the zerotree coder of pgc/zerotree_coder.h, one packet per
// bitplane spanning every subband and component. It exists to be compared
// with SIM and 3xC (rate_distortion.h); it is not a .mwv format: there is no
// resolution order and no packet can be skipped, only truncated.
#ifndef MESHWAVE_PGC_PGC_STREAM_H_
#define MESHWAVE_PGC_PGC_STREAM_H_

#include <array>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "meshwave/encoder.h"
#include "meshwave/progressive_decoder.h"
#include "meshwave/semiregular.h"
#include "meshwave/status.h"
#include "meshwave/wavelet.h"
#include "pgc/zerotree_coder.h"
#include "stream/base_mesh_decoder.h"
#include "stream/packet_index.h"

namespace meshwave {

// The value of StreamHeader.coder in a PGC header. Deliberately not in
// stream.proto: PGC headers never go into a .mwv stream, and with this value
// ValidateStreamHeader (hence ProgressiveDecoder) refuses them as an unknown
// coder instead of misreading their packets. Only this folder names it.
inline constexpr int32_t kPgcCoderValue = 2;

// The distortion chain of each packet of a PGC header (stream/packet_index.h):
// one chain, 0, for all, since a packet spans every subband.
std::vector<uint32_t> PgcPacketChains(const StreamHeader& header);

// A PGC encoding. `header` is a StreamHeader as EncodeMesh fills it (base
// mesh, transform, quantizers, bounding box, base distortion) except that
// coder is kPgcCoderValue, octree_leaf_size is 0 and the packet index has
// one entry per bitplane, from the highest top bitplane of any (subband,
// component) down to 0, all in one distortion chain (a packet spans all
// subbands).
// ContainerSize(header, ids) therefore counts a PGC stream as it counts a
// 3xC one.
struct PgcStream {
  StreamHeader header;
  std::vector<std::string> packets;  // packets[i] codes bitplane top - i
  // The encoded mesh as the stream numbers it (base in transmission order,
  // as EncodedStream::mesh): PgcDecoder returns vertices in this order.
  SemiRegularMesh mesh;
};

// Encodes with the transform, precision and deadzone of `options` (its
// coder and octree_leaf_size are ignored), after the same base renumbering
// as EncodeMesh. Same errors as EncodeMesh.
Result<PgcStream> EncodePgc(const SemiRegularMesh& mesh,
                            const EncodeOptions& options);

// Decodes a PGC stream packet by packet, in bitplane order; the mesh can be
// reconstructed after any number of packets. Checks the header (counts,
// ranges, hierarchy limits) and every packet (length, CRC-16 check, symbols within
// the payload), so it does not crash on corrupt input, but it is a
// measurement tool, not a hardened network decoder.
class PgcDecoder {
 public:
  static Result<std::unique_ptr<PgcDecoder>> Create(
      const StreamHeader& header, const DecoderOptions& options = {});

  size_t packet_count() const { return header_.packets.length.size(); }
  size_t packets_decoded() const { return decoded_; }
  // Packet i codes bitplane top_bitplane() - i.
  int top_bitplane() const { return top_; }

  // Decodes the next packet. Errors: all packets decoded already
  // (kInvalidArgument), length or CRC mismatch (kParseError, nothing
  // changed), symbols beyond the payload (kParseError; the decoder is then
  // unusable).
  Status AddPacket(std::string_view payload);

  // The finest level's positions in canonical order (base mesh and the
  // coefficients known so far, each at its cell's reconstruction point).
  std::vector<Vec3> Positions() const;

 private:
  PgcDecoder() = default;

  StreamHeader header_;
  DecoderOptions options_;
  std::shared_ptr<const SemiRegularHierarchy> hierarchy_;
  std::unique_ptr<WaveletTransform> transform_;
  DecodedBase base_;
  std::array<ZerotreeState, 3> states_;
  int top_ = -1;
  size_t decoded_ = 0;
  bool broken_ = false;
};

}  // namespace meshwave

#endif  // MESHWAVE_PGC_PGC_STREAM_H_
