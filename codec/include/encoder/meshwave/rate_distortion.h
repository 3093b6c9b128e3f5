// Rate-distortion curves of the bitplane coders (Satti et al.
// 2011, Figs. 9-10): PSNR against rate after each packet of the quality order.
#ifndef MESHWAVE_RATE_DISTORTION_H_
#define MESHWAVE_RATE_DISTORTION_H_

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "meshwave/encoder.h"
#include "meshwave/semiregular.h"
#include "meshwave/status.h"

namespace meshwave {

enum class RdCoder {
  k3xC,  // EncodeMesh, CoderKind::k3xC
  kSim,  // EncodeMesh, CoderKind::kSim
  kPgc,  // the zerotree baseline (one packet per bitplane)
};
Result<RdCoder> ParseRdCoder(const std::string& name);  // "3xc", "sim", "pgc"
const char* RdCoderName(RdCoder coder);

// The state after a prefix of the quality order.
struct RdPoint {
  size_t packets = 0;          // packets decoded
  uint64_t bytes_total = 0;    // container: preamble, header with base mesh, payloads
  uint64_t payload_bytes = 0;  // the packets' payloads only
  double bpv_total = 0;        // 8 bytes_total / V_J
  double bpv_excl_base = 0;    // 8 payload_bytes / V_J, as Satti et al. 2011's figures
  double psnr_db = 0;          // 20 log10(diagonal / RMS), same-index vertices
  // b when this prefix holds every packet of bitplanes >= b and none below,
  // else -1. All coders quantise alike, so at the same b they reconstruct
  // the same mesh (same PSNR): comparing their rates there is exact.
  int bitplane_complete = -1;
};

struct RdCurve {
  RdCoder coder = RdCoder::k3xC;
  uint64_t vertices = 0;  // V_J
  // points[0]: no packet (the base mesh alone), then one point after each
  // packet. bpv_excl_base never decreases along the curve. The curve is
  // packet-granular: no point falls inside a packet, although every coder
  // here could stop mid-packet (a PGC packet is a whole bitplane, so its
  // curve is the coarsest).
  std::vector<RdPoint> points;
};

// Encodes `mesh` with `coder` (transform, precision and deadzone from
// `options`; its `coder` field is ignored), decodes the packets one by one in
// quality order and measures each prefix against the positions of `mesh`
// (vertex by vertex, in the order of the stream's own copy of the mesh, as
// the encoders renumber the base; PSNR peak: their bounding-box diagonal).
// Errors: those of the encoder.
Result<RdCurve> MeasureRdCurve(const SemiRegularMesh& mesh, RdCoder coder,
                               const EncodeOptions& options);

// The point of `curve` where bitplane b is complete, or null.
const RdPoint* PointAtBitplane(const RdCurve& curve, int b);

// PSNR at `bpv_excl_base` by linear interpolation between the two points of
// the curve around it; NaN when it lies outside the curve.
double PsnrAtBpv(const RdCurve& curve, double bpv_excl_base);

// The rates of the comparison table (bits per vertex, base mesh excluded).
inline constexpr std::array<double, 5> kRdTableBpv = {0.05, 0.1, 0.2, 0.3, 0.5};

}  // namespace meshwave

#endif  // MESHWAVE_RATE_DISTORTION_H_
