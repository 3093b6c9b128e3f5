#include "stream/signal_encoder.h"

#include <algorithm>
#include <cmath>

#include "bitplane/bitplane_passes.h"
#include "bitplane/encoder_io.h"
#include "core/parallel_for.h"
#include "meshwave/packet_parts.h"
#include "quant/deadzone_choice.h"

namespace meshwave {

namespace {

// The largest subband (the finest) first: it takes about 3/4 of the work.
int FinestFirst(size_t levels, size_t i) { return static_cast<int>(levels - 1 - i); }

using PerPrecinct = std::vector<std::array<std::vector<uint32_t>, 3>>;
using SignsPerPrecinct = std::vector<std::array<std::vector<uint8_t>, 3>>;

// Codes the packets of subband j, bitplanes from the top down; packets
// (j, b) with b < split hold one codeword per precinct (FORMAT.md 2.2),
// the others one codeword for all, precinct after precinct.
std::vector<CodedPacket> CodeSubband(const QuantizedSignal& signal,
                                     const std::vector<std::vector<SubbandLayout>>& layouts,
                                     const std::vector<PerPrecinct>& q0_ordered,
                                     const std::vector<SignsPerPrecinct>& negative_ordered,
                                     double gain, CoderKind coder, int j, uint32_t split) {
  const std::vector<SubbandLayout>& precincts = layouts[j];
  const auto& quantized = signal.subbands[j];
  std::vector<std::array<ComponentState, 3>> state(precincts.size());
  int top = -1;
  for (int c = 0; c < 3; ++c) top = std::max(top, quantized[c].top);
  for (size_t p = 0; p < precincts.size(); ++p) {
    for (int c = 0; c < 3; ++c) state[p][c].Init(precincts[p].tree, quantized[c].top);
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
        const QuantizedComponent& q = quantized[c];
        if (b > q.top) continue;
        ContextSources sources;
        if (coder == CoderKind::k3xC) {
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
          reduction += q.weight * gain *
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
}

}  // namespace

SignalScale GeometryScale(const PreparedStream& prepared) {
  const double t = prepared.tangent_step_scale;
  return {prepared.step0, {1.0, t, t}, prepared.gains.subband};
}

QuantizedSignal QuantizeSignal(const std::vector<std::vector<Vec3>>& subbands,
                               const SignalScale& scale, int deadzone, bool auto_deadzone,
                               int threads, std::span<double> energy) {
  const size_t levels = subbands.size();
  QuantizedSignal out;
  out.subbands.resize(levels);
  out.deadzones.resize(levels);
  // A task per subband: its three components in order, so that the energy
  // of its chain sums in a fixed order.
  ParallelTasks(levels, threads, [&](size_t i) {
    const int j = FinestFirst(levels, i);
    const double gain = scale.gains[static_cast<size_t>(j)];
    for (int c = 0; c < 3; ++c) {
      const auto& band = subbands[static_cast<size_t>(j)];
      std::vector<double> values(band.size());
      for (size_t k = 0; k < band.size(); ++k) values[k] = band[k][c];
      const int code = auto_deadzone ? ChooseDeadzoneCode(values, deadzone) : deadzone;
      out.deadzones[j][c] = code;
      const double s = scale.component_scale[static_cast<size_t>(c)];
      out.subbands[j][c] = QuantizeAtStep(std::move(values), scale.step0 / std::sqrt(gain) * s,
                                          1 / (s * s), gain, code, energy[j]);
    }
  });
  return out;
}

void AppendQuantizers(const QuantizedSignal& signal,
                      google::protobuf::RepeatedPtrField<proto::Quantizer>& out) {
  for (size_t j = 0; j < signal.subbands.size(); ++j) {
    for (int c = 0; c < 3; ++c) AppendQuantizer(signal.subbands[j][c], signal.deadzones[j][c], out);
  }
}

CodedSignal CodeSignal(const QuantizedSignal& signal,
                       const std::vector<std::vector<SubbandLayout>>& layouts,
                       const SignalScale& scale, CoderKind coder,
                       uint32_t split_bytes_per_precinct, int threads) {
  const size_t levels = signal.subbands.size();
  // The coder names coefficients by Morton position: q0 and signs in each
  // precinct's octree order.
  std::vector<PerPrecinct> q0_ordered(levels);
  std::vector<SignsPerPrecinct> negative_ordered(levels);
  ParallelTasks(levels, threads, [&](size_t i) {
    const int j = FinestFirst(levels, i);
    const size_t count = layouts[j].size();
    q0_ordered[j].resize(count);
    negative_ordered[j].resize(count);
    for (size_t p = 0; p < count; ++p) {
      for (int c = 0; c < 3; ++c) {
        const QuantizedComponent& q = signal.subbands[j][c];
        q0_ordered[j][p][c] = InMortonOrder<uint32_t>(layouts[j][p], q.q0);
        negative_ordered[j][p][c] = InMortonOrder<uint8_t>(layouts[j][p], q.negative);
      }
    }
  });
  auto code = [&](int j, uint32_t split) {
    return CodeSubband(signal, layouts, q0_ordered, negative_ordered,
                       scale.gains[static_cast<size_t>(j)], coder, j, split);
  };
  // Subbands share nothing but read-only inputs (3xC reads the parent
  // subband's q0 and signs), so each is coded by its own task. A subband
  // of several precincts is coded unsplit first: its packets' sizes say
  // which bitplanes are worth splitting (the low ones, where the bytes are).
  CodedSignal out;
  out.subbands.resize(levels);
  out.split_planes.assign(levels, 0);
  ParallelTasks(levels, threads, [&](size_t i) {
    const int j = FinestFirst(levels, i);
    out.subbands[j] = code(j, 0);
    const uint64_t precincts = layouts[j].size();
    if (precincts < 2) return;
    uint32_t split = 0;
    for (auto packet = out.subbands[j].rbegin(); packet != out.subbands[j].rend();
         ++packet, ++split) {
      if (packet->payload.size() < uint64_t{split_bytes_per_precinct} * precincts) break;
    }
    out.split_planes[static_cast<size_t>(j)] = split;
  });
  // A packet (j, b) sent whole needs every part of (j - 1, b) (3xC's
  // parent contexts): a subband splits at least the bitplanes its parent
  // subband splits, so that a region's part of a finer subband never
  // drags in a coarser subband's whole bitplane.
  for (size_t j = 1; j < levels; ++j) {
    if (layouts[j].size() < 2) continue;
    auto& split = out.split_planes[j];
    split = std::max(split, std::min(out.split_planes[j - 1],
                                     static_cast<uint32_t>(out.subbands[j].size())));
  }
  ParallelTasks(levels, threads, [&](size_t i) {
    const int j = FinestFirst(levels, i);
    if (out.split_planes[static_cast<size_t>(j)] > 0) {
      out.subbands[j] = code(j, out.split_planes[static_cast<size_t>(j)]);
    }
  });
  return out;
}

}  // namespace meshwave
