// EncodeMesh: transform, quantise, and code every (subband, bitplane)
// packet. See docs/FORMAT.md for what each step writes.
#include <cmath>
#include <string>

#include "bitplane/bitplane_io.h"
#include "bitplane/bitplane_passes.h"
#include "bitplane/subband_layout.h"
#include "meshwave/encoder.h"
#include "quant/deadzone_choice.h"
#include "quant/deadzone_quantizer.h"
#include "quant/subband_gains.h"
#include "stream/base_mesh_codec.h"
#include "stream/distortion_index_writer.h"
#include "stream/packet_index.h"
#include "stream/stream_preparation.h"
#include "wavelet/sawt_choice.h"
#include "stream/stream_format.h"
#include "stream/stream_format_writer.h"

namespace meshwave {
namespace {

// Quantised coefficients of one (subband, component).
struct QuantizedComponent {
  std::vector<double> value;
  std::vector<uint32_t> q0;
  std::vector<uint8_t> negative;
  double step = 0;
  double xi0 = 0;
  int top = -1;
};

double SquaredError(double x, uint32_t mag, int n, bool negative,
                    const QuantizedComponent& q) {
  const double r =
      (mag >> n) == 0 ? 0.0 : Dequantize(mag >> n, n, negative, q.step, q.xi0);
  return (x - r) * (x - r);
}

}  // namespace

Result<CoderKind> ParseCoderKind(const std::string& name) {
  if (name == "3xc" || name == "3xC") return CoderKind::k3xC;
  if (name == "sim") return CoderKind::kSim;
  return InvalidArgument("unknown coder \"" + name + "\" (expected 3xc or sim)");
}

const char* CoderKindName(CoderKind coder) {
  return coder == CoderKind::k3xC ? "3xc" : "sim";
}

Result<EncodedStream> EncodeMesh(const SemiRegularMesh& input,
                                 const EncodeOptions& options) {
  MW_ASSIGN_OR_RETURN(PreparedStream prepared, PrepareStream(input, options));
  EncodedStream out;
  out.mesh = std::move(prepared.mesh);
  if (prepared.transform.sawt) {
    const auto usage = SawtFilterUsage(*out.mesh.hierarchy, *prepared.transform.sawt);
    out.sawt_filter_usage.assign(usage.begin(), usage.end());
    out.sawt_regions = prepared.transform.sawt->regions.count;
  }
  const SemiRegularMesh& mesh = out.mesh;
  const SemiRegularHierarchy& h = *mesh.hierarchy;
  const int levels = h.levels();
  const double step0 = prepared.step0;
  const SubbandGains& gains = prepared.gains;
  const Pyramid& pyramid = prepared.pyramid;
  const DecodedBase& base = prepared.base;
  proto::StreamHeader& header = prepared.header;
  header.set_coder(options.coder == CoderKind::k3xC ? proto::CODER_3XC
                                                    : proto::CODER_SIM);
  header.set_octree_leaf_size(options.octree_leaf_size);
  DistortionModel model;
  model.base = prepared.base_distortion;
  model.chain_start.assign(static_cast<size_t>(levels), 0.0);
  const auto layouts =
      BuildSubbandLayouts(h, base.grid, options.octree_leaf_size);

  // Quantise every (subband, component).
  std::vector<std::array<QuantizedComponent, 3>> quantized(levels);
  for (int j = 0; j < levels; ++j) {
    const auto& band = pyramid.subbands[j];
    for (int c = 0; c < 3; ++c) {
      QuantizedComponent& q = quantized[j][c];
      q.step = step0 / std::sqrt(gains.subband[j]);
      q.value.resize(band.size());
      for (size_t k = 0; k < band.size(); ++k) q.value[k] = band[k][c];
      const int deadzone = options.auto_deadzone
                               ? ChooseDeadzoneCode(q.value, options.deadzone)
                               : options.deadzone;
      q.xi0 = DeadzoneXi(deadzone);
      q.q0.resize(band.size());
      q.negative.resize(band.size());
      uint32_t max_q = 0;
      for (size_t k = 0; k < band.size(); ++k) {
        q.q0[k] = QuantizeMagnitude(q.value[k], q.step, q.xi0);
        q.negative[k] = q.value[k] < 0;
        max_q = std::max(max_q, q.q0[k]);
        model.chain_start[j] += gains.subband[j] * q.value[k] * q.value[k];
      }
      q.top = TopBitplane(max_q);
      proto::Quantizer* pq = header.add_quantizers();
      pq->set_step(q.step);
      pq->set_deadzone(static_cast<uint32_t>(deadzone));
      pq->set_top_bitplane(q.top);
    }
  }

  // Code the packets, subband by subband, bitplanes from the top down.
  proto::PacketIndex& index = *header.mutable_packets();
  std::vector<uint32_t> touched;
  for (int j = 0; j < levels; ++j) {
    const SubbandLayout& layout = layouts[j];
    std::array<ComponentState, 3> state;
    int top = -1;
    for (int c = 0; c < 3; ++c) {
      state[c].Init(layout.tree, quantized[j][c].top);
      top = std::max(top, quantized[j][c].top);
    }
    for (int b = top; b >= 0; --b) {
      ArithmeticEncoder enc;
      ComponentContexts contexts;  // shared by the packet's three components
      double reduction = 0;
      for (int c = 0; c < 3; ++c) {
        const QuantizedComponent& q = quantized[j][c];
        if (b > q.top) continue;
        ParentView parent;
        if (options.coder == CoderKind::k3xC && j > 0) {
          parent = {layout.parent_of, quantized[j - 1][c].q0,
                    quantized[j - 1][c].negative};
        }
        EncoderIo io(enc, layout.tree, q.q0, q.negative);
        touched.clear();
        CodeBitplane(layout.tree, state[c], b, parent, contexts, io, &touched);
        for (uint32_t k : touched) {
          const uint32_t mag = state[c].mag[k];
          const uint32_t before = mag & ~(1u << b);
          reduction += gains.subband[j] *
                       (SquaredError(q.value[k], before, b + 1, q.negative[k], q) -
                        SquaredError(q.value[k], mag, b, q.negative[k], q));
        }
      }
      std::string payload = enc.Finish();
      index.add_length(static_cast<uint32_t>(payload.size()));
      const uint16_t check = PacketCheck(payload);
      index.mutable_check()->push_back(static_cast<char>(check >> 8));
      index.mutable_check()->push_back(static_cast<char>(check & 0xff));
      model.chain.push_back(static_cast<uint32_t>(j));
      model.reduction.push_back(reduction);
      out.packets.push_back(std::move(payload));
    }
  }
  WriteDistortionIndex(model, prepared.zero_packet_distortion, header);
  MW_ASSIGN_OR_RETURN(out.header, ToStreamHeader(header));
  return out;
}

}  // namespace meshwave
