// The encoders' side of the compact packet index (stream/packet_index.h
// holds the model and the readers' side): the distortion figures written
// into the header.
#ifndef MESHWAVE_STREAM_DISTORTION_INDEX_WRITER_H_
#define MESHWAVE_STREAM_DISTORTION_INDEX_WRITER_H_

#include <algorithm>
#include <cstdint>
#include <limits>
#include <string_view>
#include <vector>

#include "stream.pb.h"

namespace meshwave {

// What an encoder measured, in the model's units, before the index is
// written: chain of every packet (ids in index order, each chain's packets
// in decoding order) and each packet's estimated distortion reduction.
struct DistortionModel {
  double base = 0;                  // error of the decoded base alone
  std::vector<double> chain_start;  // per chain, nothing of it decoded
  std::vector<uint32_t> chain;      // per packet
  std::vector<double> reduction;    // per packet
  // Chains from this one on are a channel's (in its own units): not summed
  // into the geometry's start, not scaled.
  size_t geometry_chains = std::numeric_limits<size_t>::max();

  // Adds a chain of another signal (a channel's subband, a texture map,
  // the original layer), after the geometry's; returns its index.
  uint32_t AddOtherChain(double start) {
    geometry_chains = std::min(geometry_chains, chain_start.size());
    chain_start.push_back(start);
    return static_cast<uint32_t>(chain_start.size() - 1);
  }
};

// Writes base_distortion, chain_distortion and distortion_step, scaling
// every figure of the geometry so that the estimate with no packet equals
// `true_start_distortion` (when it and the model's are positive). Why the
// scale: the encoders estimate with subband gains, as if the synthesis were
// orthogonal. It is not (Loop's predictor least of all: the model was 3 to
// 4.5 dB pessimistic at low rates), so anchoring the start to the truth
// keeps every PSNR read off the index close to it.
void WriteDistortionIndex(const DistortionModel& model, double true_start_distortion,
                          proto::StreamHeader& header);

// Records a coded packet, the next id: its length and check in `index`, its
// chain and estimated distortion reduction in `model`.
void AddCodedPacket(std::string_view payload, uint32_t chain, double reduction,
                    proto::PacketIndex& index, DistortionModel& model);

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_DISTORTION_INDEX_WRITER_H_
