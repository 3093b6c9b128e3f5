// EncodeMesh: transform, quantise, and code every (subband, bitplane)
// packet. See docs/FORMAT.md for what each step writes.
#include <algorithm>
#include <cmath>
#include <span>
#include <string>

#include "bitplane/subband_layout.h"
#include "meshwave/encoder.h"
#include "stream/original_layer_encoder.h"
#include "quant/subband_gains.h"
#include "stream/base_mesh_decoder.h"
#include "stream/base_refinement_encoder.h"
#include "stream/channel_encoder.h"
#include "stream/distortion_index_writer.h"
#include "stream/packet_index.h"
#include "stream/precinct_partition.h"
#include "stream/stream_format.h"
#include "stream/stream_format_writer.h"
#include "stream/signal_encoder.h"
#include "stream/stream_preparation.h"
#include "stream/texture_encoder.h"
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
  return EncodeMesh(input, options, {});
}

Result<EncodedStream> EncodeMesh(const SemiRegularMesh& input, const EncodeOptions& options,
                                 const VertexAttributes& attributes) {
  MW_ASSIGN_OR_RETURN(PreparedStream prepared, PrepareStream(input, options));
  if (!attributes.colors.empty() && attributes.colors.size() != input.positions.size()) {
    return InvalidArgument(std::to_string(attributes.colors.size()) +
                           " vertex colours for a mesh of " +
                           std::to_string(input.positions.size()) + " vertices");
  }
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

  // The geometry is a signal like any channel: quantised (the quantizers
  // in (subband, component) order) and coded by the same functions.
  const SignalScale scale = GeometryScale(prepared);
  const QuantizedSignal quantized =
      QuantizeSignal(prepared.pyramid.subbands, scale, options.deadzone, options.auto_deadzone,
                     options.threads, std::span<double>(model.chain_start).first(levels));
  AppendQuantizers(quantized, *header.mutable_quantizers());
  CodedSignal coded = CodeSignal(quantized, layouts, scale, options.coder,
                                 options.split_bytes_per_precinct, options.threads);
  const std::vector<uint32_t>& split_planes = coded.split_planes;
  proto::PacketIndex& index = *header.mutable_packets();
  // Absent when nothing is split: a stream without precincts pays nothing.
  if (std::any_of(split_planes.begin(), split_planes.end(), [](uint32_t s) { return s > 0; })) {
    for (uint32_t split : split_planes) index.add_split_planes(split);
  }
  for (int j = 0; j < levels; ++j) {
    for (CodedPacket& packet : coded.subbands[j]) {
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
  // The colour channel after the geometry: its packets follow the base
  // refinement's, its chains the geometry's (FORMAT.md 2.3).
  if (!attributes.colors.empty()) {
    out.colors.resize(attributes.colors.size());
    for (size_t v = 0; v < out.colors.size(); ++v) {
      out.colors[v] = attributes.colors[prepared.input_vertex[v]];
    }
    MW_ASSIGN_OR_RETURN(EncodedChannel channel,
                        EncodeColorChannel(prepared, out.mesh, out.colors, layouts, options));
    const auto first_chain = static_cast<uint32_t>(model.chain_start.size());
    for (double start : channel.chain_start) model.AddOtherChain(start);
    for (int j = 0; j < levels; ++j) {
      for (CodedPacket& packet : channel.coded.subbands[static_cast<size_t>(j)]) {
        AddCodedPacket(packet.payload, first_chain + static_cast<uint32_t>(j),
                       packet.reduction, index, model);
        out.packets.push_back(std::move(packet.payload));
      }
    }
    *header.add_channels() = std::move(channel.header);
  }
  // The texture's levels last, a chain per map (FORMAT.md 2.4).
  if (attributes.texture) {
    MW_ASSIGN_OR_RETURN(EncodedTexture texture,
                        EncodeTexture(*attributes.texture, input, out.mesh, prepared.input_vertex,
                                      static_cast<uint32_t>(out.packets.size()), options));
    const auto first_chain = static_cast<uint32_t>(model.chain_start.size());
    for (double start : texture.chain_start) model.AddOtherChain(start);
    size_t next = 0;
    for (int m = 0; m < texture.header.maps_size(); ++m) {
      for (int k = 0; k < texture.header.maps(m).levels_size(); ++k, ++next) {
        AddCodedPacket(texture.packets[next], first_chain + static_cast<uint32_t>(m),
                       texture.reduction[next], index, model);
        out.packets.push_back(std::move(texture.packets[next]));
      }
    }
    *header.mutable_texture() = std::move(texture.header);
  }
  // The original layer after everything, one chain (FORMAT.md 2.5).
  if (attributes.original) {
    MW_ASSIGN_OR_RETURN(
        original::EncodedLayer layer,
        original::EncodeLayer(*attributes.original, attributes.original_remesh_psnr_db,
                              header.vertices(), options.precision,
                              options.original_refinement_planes));
    const uint32_t chain = model.AddOtherChain(layer.chain_start);
    for (size_t i = 0; i < layer.packets.size(); ++i) {
      AddCodedPacket(layer.packets[i], chain, layer.reduction[i], index, model);
      out.packets.push_back(std::move(layer.packets[i]));
    }
    *header.mutable_original() = std::move(layer.header);
  }
  WriteDistortionIndex(model, prepared.zero_packet_distortion, header);
  MW_ASSIGN_OR_RETURN(out.header, ToStreamHeader(header));
  return out;
}

}  // namespace meshwave
