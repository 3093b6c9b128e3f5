// EncodeMesh: transform, quantise, and code every (subband, bitplane)
// packet. See docs/FORMAT.md for what each step writes.
#include <cmath>
#include <string>

#include "bitplane/bitplane_io.h"
#include "bitplane/bitplane_passes.h"
#include "bitplane/subband_layout.h"
#include "core/parallel_for.h"
#include "meshwave/encoder.h"
#include "quant/deadzone_choice.h"
#include "quant/deadzone_quantizer.h"
#include "quant/subband_gains.h"
#include "stream/base_mesh_codec.h"
#include "stream/base_refinement.h"
#include "stream/distortion_index_writer.h"
#include "stream/packet_index.h"
#include "stream/stream_format.h"
#include "stream/stream_format_writer.h"
#include "stream/stream_preparation.h"
#include "wavelet/sawt_choice.h"

namespace meshwave {

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
  const SubbandGains& gains = prepared.gains;
  const DecodedBase& base = prepared.base;
  proto::StreamHeader& header = prepared.header;
  header.set_coder(options.coder == CoderKind::k3xC ? proto::CODER_3XC
                                                    : proto::CODER_SIM);
  header.set_octree_leaf_size(options.octree_leaf_size);
  DistortionModel model;
  model.base = prepared.base_distortion;
  // A chain per subband, then the base refinement's (packet_index.h).
  model.chain_start.assign(static_cast<size_t>(levels) + 1, 0.0);
  const std::vector<double>& base_error = prepared.base_error;
  model.chain_start[static_cast<size_t>(levels)] = base_error.back() - base_error.front();
  const auto layouts =
      BuildSubbandLayouts(h, base.grid, options.octree_leaf_size);

  // Quantise every (subband, component): a task per subband (its three
  // components in order, so the energy of its chain sums as it always
  // did), the quantizers appended to the header in (subband, component)
  // order afterwards.
  std::vector<std::array<QuantizedComponent, 3>> quantized(levels);
  std::vector<std::array<int, 3>> deadzones(levels);
  // The largest subband (the finest) first: it takes about 3/4 of the work.
  const auto finest_first = [levels](size_t i) { return levels - 1 - static_cast<int>(i); };
  ParallelTasks(static_cast<size_t>(levels), options.threads, [&](size_t i) {
    const int j = finest_first(i);
    for (int c = 0; c < 3; ++c) {
      std::vector<double> values = SubbandComponent(prepared, j, c);
      deadzones[j][c] = options.auto_deadzone ? ChooseDeadzoneCode(values, options.deadzone)
                                              : options.deadzone;
      quantized[j][c] = QuantizeValues(prepared, j, c, std::move(values), deadzones[j][c],
                                       model.chain_start[j]);
    }
  });
  for (int j = 0; j < levels; ++j) {
    for (int c = 0; c < 3; ++c) AppendQuantizer(quantized[j][c], deadzones[j][c], header);
  }

  // The coder names coefficients by Morton position: q0 and signs in each
  // subband's octree order.
  std::vector<std::array<std::vector<uint32_t>, 3>> q0_ordered(levels);
  std::vector<std::array<std::vector<uint8_t>, 3>> negative_ordered(levels);
  ParallelTasks(static_cast<size_t>(levels), options.threads, [&](size_t i) {
    const int j = finest_first(i);
    for (int c = 0; c < 3; ++c) {
      q0_ordered[j][c] = InMortonOrder<uint32_t>(layouts[j].tree, quantized[j][c].q0);
      negative_ordered[j][c] = InMortonOrder<uint8_t>(layouts[j].tree, quantized[j][c].negative);
    }
  });

  // Code the packets, subband by subband, bitplanes from the top down.
  // Subbands share nothing but read-only inputs (3xC reads the parent
  // subband's q0 and signs), so each is coded by its own task; the packets
  // enter the index in (subband, bitplane) order afterwards.
  struct CodedPacket {
    std::string payload;
    double reduction = 0;
  };
  std::vector<std::vector<CodedPacket>> coded(levels);
  ParallelTasks(static_cast<size_t>(levels), options.threads, [&](size_t i) {
    const int j = finest_first(i);
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
        ContextSources sources;
        if (options.coder == CoderKind::k3xC) {
          if (j > 0) {
            sources = {layout.parent_position, q0_ordered[j - 1][c], negative_ordered[j - 1][c], {}};
          }
          sources.neighbour_position = layout.neighbour_position;
        }
        EncoderIo io(enc, q0_ordered[j][c], negative_ordered[j][c]);
        CodeBitplane(layout.tree, state[c], b, sources, contexts, io);
        // Every significant coefficient's reconstruction changed.
        for (uint32_t s : state[c].significant()) {
          const uint32_t mag = state[c].mag[s];
          const uint32_t before = mag & ~(1u << b);
          const uint32_t k = layout.tree.At(s);
          reduction += q.weight * gains.subband[j] *
                       (q.SquaredError(k, before, b + 1) - q.SquaredError(k, mag, b));
        }
      }
      coded[j].push_back({enc.Finish(), reduction});
    }
  });
  proto::PacketIndex& index = *header.mutable_packets();
  for (int j = 0; j < levels; ++j) {
    for (CodedPacket& packet : coded[j]) {
      AddCodedPacket(packet.payload, static_cast<uint32_t>(j), packet.reduction, index, model);
      out.packets.push_back(std::move(packet.payload));
    }
  }
  // The base refinement: plane R-1 first; each takes the base's error from
  // base_error[b + 1] to base_error[b].
  for (int b = static_cast<int>(base_error.size()) - 2; b >= 0; --b) {
    std::string payload = EncodeBaseRefinementPlane(prepared.base_residual, b);
    AddCodedPacket(payload, static_cast<uint32_t>(levels),
                   base_error[static_cast<size_t>(b) + 1] - base_error[static_cast<size_t>(b)],
                   index, model);
    out.packets.push_back(std::move(payload));
  }
  WriteDistortionIndex(model, prepared.zero_packet_distortion, header);
  MW_ASSIGN_OR_RETURN(out.header, ToStreamHeader(header));
  return out;
}

}  // namespace meshwave
