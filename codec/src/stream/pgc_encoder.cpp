// EncodePgc: EncodeMesh's transform, base mesh and quantisers, then the
// zerotree coder, one packet per bitplane.
#include <cmath>
#include <string>

#include "quant/deadzone_quantizer.h"
#include "quant/subband_gains.h"
#include "stream/distortion_index_writer.h"
#include "stream/packet_index.h"
#include "stream/pgc_stream.h"
#include "stream/stream_preparation.h"
#include "stream/stream_format.h"
#include "stream/stream_format_writer.h"

namespace meshwave {
namespace {

// Magnitudes, signs and values of one component, per subband.
struct QuantizedTrees {
  std::vector<std::vector<uint32_t>> q0;
  std::vector<std::vector<uint8_t>> negative;
  std::vector<std::vector<double>> value;
  std::vector<int> top;
};

double SquaredError(double x, uint32_t mag, int n, bool negative, double step,
                    double xi0) {
  const double r =
      (mag >> n) == 0 ? 0.0 : Dequantize(mag >> n, n, negative, step, xi0);
  return (x - r) * (x - r);
}

}  // namespace

Result<PgcStream> EncodePgc(const SemiRegularMesh& input,
                            const EncodeOptions& options) {
  // The checks, steps and header fields below follow EncodeMesh exactly, so
  // that PGC, SIM and 3xC code the same quantised coefficients
  // (ZerotreeCoderTest.UsesTheQuantizersAndVertexOrderOfEncodeMesh pins it).
  MW_ASSIGN_OR_RETURN(PreparedStream prepared, PrepareStream(input, options));
  PgcStream out;
  out.mesh = std::move(prepared.mesh);
  const SemiRegularMesh& mesh = out.mesh;
  const SemiRegularHierarchy& h = *mesh.hierarchy;
  const int levels = h.levels();
  const double step0 = prepared.step0;
  const SubbandGains& gains = prepared.gains;
  const Pyramid& pyramid = prepared.pyramid;
  proto::StreamHeader& header = prepared.header;
  header.set_coder(static_cast<proto::Coder>(kPgcCoderValue));
  DistortionModel model;
  model.base = prepared.base_distortion;
  model.chain_start.assign(1, 0.0);

  const double xi0 = DeadzoneXi(options.deadzone);
  std::vector<double> steps(levels);
  std::array<QuantizedTrees, 3> trees;
  for (auto& t : trees) {
    t.q0.resize(levels);
    t.negative.resize(levels);
    t.value.resize(levels);
    t.top.assign(levels, -1);
  }
  for (int j = 0; j < levels; ++j) {
    steps[j] = step0 / std::sqrt(gains.subband[j]);
    const auto& band = pyramid.subbands[j];
    for (int c = 0; c < 3; ++c) {
      QuantizedTrees& t = trees[c];
      t.q0[j].resize(band.size());
      t.negative[j].resize(band.size());
      t.value[j].resize(band.size());
      uint32_t max_q = 0;
      for (size_t k = 0; k < band.size(); ++k) {
        const double x = band[k][c];
        t.value[j][k] = x;
        t.q0[j][k] = QuantizeMagnitude(x, steps[j], xi0);
        t.negative[j][k] = x < 0;
        max_q = std::max(max_q, t.q0[j][k]);
        model.chain_start[0] += gains.subband[j] * x * x;
      }
      t.top[j] = TopBitplane(max_q);
      proto::Quantizer* pq = header.add_quantizers();
      pq->set_step(steps[j]);
      pq->set_deadzone(static_cast<uint32_t>(options.deadzone));
      pq->set_top_bitplane(t.top[j]);
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
        const double x = trees[c].value[n.j][n.k];
        const bool neg = trees[c].negative[n.j][n.k];
        reduction += gains.subband[n.j] *
                     (SquaredError(x, mag & ~(1u << b), b + 1, neg, steps[n.j], xi0) -
                      SquaredError(x, mag, b, neg, steps[n.j], xi0));
      }
    }
    std::string payload = enc.Finish();
    index.add_length(static_cast<uint32_t>(payload.size()));
    const uint16_t check = PacketCheck(payload);
    index.mutable_check()->push_back(static_cast<char>(check >> 8));
    index.mutable_check()->push_back(static_cast<char>(check & 0xff));
    model.chain.push_back(0);
    model.reduction.push_back(reduction);
    out.packets.push_back(std::move(payload));
  }
  WriteDistortionIndex(model, prepared.zero_packet_distortion, header);
  MW_ASSIGN_OR_RETURN(out.header, ToStreamHeader(header));
  return out;
}

}  // namespace meshwave
