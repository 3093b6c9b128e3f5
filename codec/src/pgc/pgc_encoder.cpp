// EncodePgc: EncodeMesh's transform, base mesh and quantisers, then the
// zerotree coder, one packet per bitplane.
#include <cmath>
#include <string>

#include "pgc/pgc_stream.h"
#include "quant/deadzone_quantizer.h"
#include "quant/subband_gains.h"
#include "stream/distortion_index_writer.h"
#include "stream/packet_index.h"
#include "stream/stream_format.h"
#include "stream/stream_format_writer.h"
#include "stream/stream_preparation.h"

namespace meshwave {
namespace {

// Magnitudes and signs of one component, per subband, as the zerotree coder
// reads them.
struct ComponentTrees {
  std::vector<std::vector<uint32_t>> q0;
  std::vector<std::vector<uint8_t>> negative;
  std::vector<int> top;
};

}  // namespace

Result<PgcStream> EncodePgc(const SemiRegularMesh& input,
                            const EncodeOptions& options) {
  // The checks, steps and header fields below follow EncodeMesh exactly, so
  // that PGC, SIM and 3xC code the same quantised coefficients
  // (ZerotreeCoderTest.UsesTheQuantizersAndVertexOrderOfEncodeMesh pins it).
  // PGC's one chain has no room for the base refinement: the whole base
  // travels in the header, as in Khodakovsky et al.'s coder.
  EncodeOptions whole_base = options;
  whole_base.base_refinement_planes = 0;
  MW_ASSIGN_OR_RETURN(PreparedStream prepared, PrepareStream(input, whole_base));
  PgcStream out;
  out.mesh = std::move(prepared.mesh);
  const SemiRegularMesh& mesh = out.mesh;
  const SemiRegularHierarchy& h = *mesh.hierarchy;
  const int levels = h.levels();
  const SubbandGains& gains = prepared.gains;
  proto::StreamHeader& header = prepared.header;
  header.set_coder(static_cast<proto::Coder>(kPgcCoderValue));
  DistortionModel model;
  model.base = prepared.base_distortion;
  model.chain_start.assign(1, 0.0);

  // One deadzone for all (auto_deadzone is not applied): PGC is measured
  // against SIM and 3xC with the same quantiser.
  std::vector<std::array<QuantizedComponent, 3>> quantized(static_cast<size_t>(levels));
  std::array<ComponentTrees, 3> trees;
  for (int j = 0; j < levels; ++j) {
    for (int c = 0; c < 3; ++c) {
      QuantizedComponent& q = quantized[j][c];
      q = QuantizeComponent(prepared, j, c, SubbandComponent(prepared, j, c), options.deadzone,
                            model.chain_start[0]);
      trees[c].q0.push_back(q.q0);
      trees[c].negative.push_back(q.negative);
      trees[c].top.push_back(q.top);
    }
  }

  std::array<ZerotreeState, 3> states;
  std::array<ZerotreeSetMaxima, 3> maxima;
  int top = -1;
  for (int c = 0; c < 3; ++c) {
    states[c].Init(h, trees[c].top);
    maxima[c] = ComputeZerotreeSetMaxima(h, trees[c].q0);
    top = std::max(top, states[c].top());
  }
  proto::PacketIndex& index = *header.mutable_packets();
  ArithmeticEncoder enc;
  for (int b = top; b >= 0; --b) {
    double reduction = 0;
    for (int c = 0; c < 3; ++c) {
      ZerotreeState& s = states[c];
      if (b > s.top()) continue;
      ZerotreeContexts contexts;
      ZerotreeEncoderIo io(enc, trees[c].q0, trees[c].negative, maxima[c]);
      CodeZerotreeBitplane(h, s, b, contexts, io);
      // Every coefficient whose reconstruction changed is significant now.
      for (const TreeNode& n : s.lsp()) {
        const uint32_t mag = s.mag(n.j)[n.k];
        const QuantizedComponent& q = quantized[n.j][c];
        reduction += q.weight * gains.subband[n.j] *
                     (q.SquaredError(n.k, mag & ~(1u << b), b + 1) - q.SquaredError(n.k, mag, b));
      }
    }
    std::string payload = enc.Finish();
    AddCodedPacket(payload, 0, reduction, index, model);
    out.packets.push_back(std::move(payload));
  }
  WriteDistortionIndex(model, prepared.zero_packet_distortion, header);
  MW_ASSIGN_OR_RETURN(out.header, ToStreamHeader(header));
  return out;
}

}  // namespace meshwave
