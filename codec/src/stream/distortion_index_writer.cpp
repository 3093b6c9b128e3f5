#include "stream/distortion_index_writer.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "stream/packet_index.h"

namespace meshwave {

void WriteDistortionIndex(const DistortionModel& model, double true_start_distortion,
                          proto::StreamHeader& header) {
  double model_start = model.base;
  for (size_t c = 0; c < model.chain_start.size() && c < model.geometry_chains; ++c) {
    model_start += model.chain_start[c];
  }
  double scale = 1;
  if (model_start > 0 && true_start_distortion > 0 && std::isfinite(model_start) &&
      std::isfinite(true_start_distortion)) {
    scale = true_start_distortion / model_start;
  }
  header.set_base_distortion(scale * model.base);
  proto::PacketIndex& index = *header.mutable_packets();
  index.clear_chain_distortion();
  // The coded (float) chain starts are the reference of each chain's first
  // step, so the decoder follows exactly the values coded here.
  const auto scale_of = [&](size_t c) { return c < model.geometry_chains ? scale : 1.0; };
  std::vector<double> coded(model.chain_start.size());
  for (size_t c = 0; c < model.chain_start.size(); ++c) {
    const float start = static_cast<float>(scale_of(c) * std::max(model.chain_start[c], 0.0));
    index.add_chain_distortion(start);
    coded[c] = start;
  }
  std::vector<double> truth(model.chain_start.size());
  for (size_t c = 0; c < truth.size(); ++c) truth[c] = scale_of(c) * model.chain_start[c];
  std::string steps(model.reduction.size(), '\0');
  for (size_t i = 0; i < model.reduction.size(); ++i) {
    const uint32_t c = model.chain[i];
    truth[c] -= scale_of(c) * model.reduction[i];
    // Closed loop: the step from the coded previous value to the true one.
    int d = 0;
    if (coded[c] > 0) {
      d = truth[c] > 0 ? static_cast<int>(std::lround(kDistortionCodesPerOctave *
                                                      std::log2(coded[c] / truth[c])))
                       : 255;
      d = std::clamp(d, 0, 255);
    }
    steps[i] = static_cast<char>(d);
    coded[c] = d == 255 ? 0.0 : coded[c] * std::exp2(-d / kDistortionCodesPerOctave);
  }
  index.set_distortion_step(steps);
}

void AddCodedPacket(std::string_view payload, uint32_t chain, double reduction,
                    proto::PacketIndex& index, DistortionModel& model) {
  index.add_length(static_cast<uint32_t>(payload.size()));
  const uint16_t check = PacketCheck(payload);
  index.mutable_check()->push_back(static_cast<char>(check >> 8));
  index.mutable_check()->push_back(static_cast<char>(check & 0xff));
  model.chain.push_back(chain);
  model.reduction.push_back(reduction);
}

}  // namespace meshwave
