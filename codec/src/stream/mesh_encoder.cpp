// EncodeMesh: transform, quantise, and code every (subband, bitplane)
// packet. See docs/FORMAT.md for what each step writes.
#include <algorithm>
#include <cmath>
#include <string>

#include "bitplane/encoder_io.h"
#include "bitplane/bitplane_passes.h"
#include "bitplane/subband_layout.h"
#include "core/parallel_for.h"
#include "meshwave/encoder.h"
#include "quant/deadzone_choice.h"
#include "quant/deadzone_quantizer.h"
#include "quant/subband_gains.h"
#include "stream/base_mesh_decoder.h"
#include "stream/base_refinement_encoder.h"
#include "stream/distortion_index_writer.h"
#include "stream/packet_index.h"
#include "meshwave/packet_parts.h"
#include "stream/precinct_partition.h"
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
  const PrecinctPartition partition =
      PartitionIntoPrecincts(h, base.grid, options.precinct_coefficients);
  const auto layouts = BuildSubbandLayouts(h, base.grid, options.octree_leaf_size,
                                           partition.FacePrecinctsPerSubband(),
                                           partition.ParentsPerSubband());
  header.mutable_packets()->set_precinct_coefficients(options.precinct_coefficients);

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
  // precinct's octree order.
  using PerPrecinct = std::vector<std::array<std::vector<uint32_t>, 3>>;
  using SignsPerPrecinct = std::vector<std::array<std::vector<uint8_t>, 3>>;
  std::vector<PerPrecinct> q0_ordered(levels);
  std::vector<SignsPerPrecinct> negative_ordered(levels);
  ParallelTasks(static_cast<size_t>(levels), options.threads, [&](size_t i) {
    const int j = finest_first(i);
    const size_t count = layouts[j].size();
    q0_ordered[j].resize(count);
    negative_ordered[j].resize(count);
    for (size_t p = 0; p < count; ++p) {
      for (int c = 0; c < 3; ++c) {
        q0_ordered[j][p][c] = InMortonOrder<uint32_t>(layouts[j][p], quantized[j][c].q0);
        negative_ordered[j][p][c] = InMortonOrder<uint8_t>(layouts[j][p], quantized[j][c].negative);
      }
    }
  });

  // Code the packets of subband j, bitplanes from the top down; packets
  // (j, b) with b < split hold one codeword per precinct (FORMAT.md 2.2),
  // the others one codeword for all, precinct after precinct.
  struct CodedPacket {
    std::string payload;
    double reduction = 0;
  };
  auto code_subband = [&](int j, uint32_t split) {
    const std::vector<SubbandLayout>& precincts = layouts[j];
    std::vector<std::array<ComponentState, 3>> state(precincts.size());
    int top = -1;
    for (int c = 0; c < 3; ++c) top = std::max(top, quantized[j][c].top);
    for (size_t p = 0; p < precincts.size(); ++p) {
      for (int c = 0; c < 3; ++c) state[p][c].Init(precincts[p].tree, quantized[j][c].top);
    }
    std::vector<CodedPacket> packets;
    // Each precinct's contexts after its share of the bitplane above: a
    // part starts from them (FORMAT.md 5.3), what a part learnt one
    // bitplane up is not learnt again.
    std::vector<ComponentContexts> carried(precincts.size());
    for (int b = top; b >= 0; --b) {
      const bool split_here = static_cast<uint32_t>(b) < split;
      ArithmeticEncoder enc;
      ComponentContexts contexts;  // shared by the codeword's components
      std::vector<std::string> parts;
      double reduction = 0;
      for (size_t p = 0; p < precincts.size(); ++p) {
        const SubbandLayout& layout = precincts[p];
        if (split_here) contexts = carried[p];
        for (int c = 0; c < 3; ++c) {
          const QuantizedComponent& q = quantized[j][c];
          if (b > q.top) continue;
          ContextSources sources;
          if (options.coder == CoderKind::k3xC) {
            if (j > 0) {
              const uint32_t up = layout.parent_precinct;
              sources = {layout.parent_position, q0_ordered[j - 1][up][c],
                         negative_ordered[j - 1][up][c], {}};
            }
            sources.neighbour_position = layout.neighbour_position;
          }
          EncoderIo io(enc, q0_ordered[j][p][c], negative_ordered[j][p][c]);
          CodeBitplane(layout.tree, state[p][c], b, sources, contexts, io);
          // Every significant coefficient's reconstruction changed.
          for (uint32_t s : state[p][c].significant()) {
            const uint32_t mag = state[p][c].mag[s];
            const uint32_t before = mag & ~(1u << b);
            const uint32_t k = layout.coefficient[s];
            reduction += q.weight * gains.subband[j] *
                         (q.SquaredError(k, before, b + 1) - q.SquaredError(k, mag, b));
          }
        }
        if (split_here) {
          parts.push_back(enc.Finish());
          carried[p] = contexts;
        }
      }
      if (!split_here) std::fill(carried.begin(), carried.end(), contexts);
      packets.push_back({split_here ? JoinPacketParts(parts) : enc.Finish(), reduction});
    }
    return packets;
  };
  // Subbands share nothing but read-only inputs (3xC reads the parent
  // subband's q0 and signs), so each is coded by its own task; the packets
  // enter the index in (subband, bitplane) order afterwards. A subband of
  // several precincts is coded unsplit first: its packets' sizes say which
  // bitplanes are worth splitting (the low ones, where the bytes are).
  std::vector<std::vector<CodedPacket>> coded(levels);
  std::vector<uint32_t> split_planes(static_cast<size_t>(levels), 0);
  ParallelTasks(static_cast<size_t>(levels), options.threads, [&](size_t i) {
    const int j = finest_first(i);
    coded[j] = code_subband(j, 0);
    const uint64_t precincts = layouts[j].size();
    if (precincts < 2) return;
    uint32_t split = 0;
    for (auto packet = coded[j].rbegin(); packet != coded[j].rend(); ++packet, ++split) {
      if (packet->payload.size() < uint64_t{options.split_bytes_per_precinct} * precincts) break;
    }
    split_planes[static_cast<size_t>(j)] = split;
  });
  // A packet (j, b) sent whole needs every part of (j - 1, b) (3xC's
  // parent contexts): a subband splits at least the bitplanes its parent
  // subband splits, so that a region's part of a finer subband never
  // drags in a coarser subband's whole bitplane.
  for (int j = 1; j < levels; ++j) {
    if (layouts[j].size() < 2) continue;
    auto& split = split_planes[static_cast<size_t>(j)];
    split = std::max(split, std::min(split_planes[static_cast<size_t>(j - 1)],
                                     static_cast<uint32_t>(coded[j].size())));
  }
  ParallelTasks(static_cast<size_t>(levels), options.threads, [&](size_t i) {
    const int j = finest_first(i);
    if (split_planes[static_cast<size_t>(j)] > 0) {
      coded[j] = code_subband(j, split_planes[static_cast<size_t>(j)]);
    }
  });
  proto::PacketIndex& index = *header.mutable_packets();
  // Absent when nothing is split: a stream without precincts pays nothing.
  if (std::any_of(split_planes.begin(), split_planes.end(), [](uint32_t s) { return s > 0; })) {
    for (uint32_t split : split_planes) index.add_split_planes(split);
  }
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
