#include "stream/packet_index.h"

#include <boost/crc.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "stream/pgc_stream.h"

namespace meshwave {

uint16_t PacketCheck(std::string_view payload) {
  boost::crc_optimal<16, 0x1021, 0xFFFF, 0, false, false> crc;
  crc.process_bytes(payload.data(), payload.size());
  return static_cast<uint16_t>(crc.checksum());
}

bool PacketCheckMatches(const proto::PacketIndex& index, uint32_t id,
                        std::string_view payload) {
  const std::string& check = index.check();
  if (check.size() < 2 * (static_cast<size_t>(id) + 1)) return false;
  const auto hi = static_cast<uint8_t>(check[2 * id]);
  const auto lo = static_cast<uint8_t>(check[2 * id + 1]);
  return PacketCheck(payload) == static_cast<uint16_t>(hi << 8 | lo);
}

PacketLayout::PacketLayout(const proto::StreamHeader& h) {
  const int levels = std::min(static_cast<int>(h.transform().levels()),
                              h.quantizers_size() / 3);
  for (int j = 0; j < levels; ++j) {
    int top = -1;
    for (int c = 0; c < 3; ++c) top = std::max(top, h.quantizers(3 * j + c).top_bitplane());
    top = std::max(top, -1);
    first_.push_back(count_);
    top_.push_back(top);
    for (int b = top; b >= 0; --b) subband_.push_back(j);
    count_ += top + 1;
  }
}

int PacketLayout::Id(int j, int b) const {
  if (j < 0 || j >= levels() || b < 0 || b > top_[static_cast<size_t>(j)]) return -1;
  return first_[static_cast<size_t>(j)] + (top_[static_cast<size_t>(j)] - b);
}

PacketLayout::Needs PacketLayout::Dependencies(uint32_t id, bool parent_contexts) const {
  Needs needs;
  if (id >= static_cast<uint32_t>(count())) return needs;
  const int j = Subband(id);
  const int b = Bitplane(id);
  if (int up = Id(j, b + 1); up >= 0) needs.ids[needs.count++] = static_cast<uint32_t>(up);
  if (parent_contexts) {
    if (int parent = Id(j - 1, b); parent >= 0) {
      needs.ids[needs.count++] = static_cast<uint32_t>(parent);
    }
  }
  return needs;
}

int PacketLayout::Bitplane(uint32_t id) const {
  const int j = subband_[id];
  return top_[static_cast<size_t>(j)] - (static_cast<int>(id) - first_[static_cast<size_t>(j)]);
}

int ChainCount(const proto::StreamHeader& header) {
  if (header.coder() == kPgcCoderValue) return 1;
  return static_cast<int>(header.transform().levels());
}

std::vector<uint32_t> PacketChains(const proto::StreamHeader& header) {
  const int count = header.packets().length_size();
  std::vector<uint32_t> chain(static_cast<size_t>(count), 0);
  if (header.coder() == kPgcCoderValue) return chain;
  const PacketLayout layout(header);
  for (int id = 0; id < count && id < layout.count(); ++id) {
    chain[static_cast<size_t>(id)] = static_cast<uint32_t>(layout.Subband(static_cast<uint32_t>(id)));
  }
  return chain;
}

void WriteDistortionIndex(const DistortionModel& model, double true_start_distortion,
                          proto::StreamHeader& header) {
  double model_start = model.base;
  for (double e : model.chain_start) model_start += e;
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
  std::vector<double> coded(model.chain_start.size());
  for (size_t c = 0; c < model.chain_start.size(); ++c) {
    const float start = static_cast<float>(scale * std::max(model.chain_start[c], 0.0));
    index.add_chain_distortion(start);
    coded[c] = start;
  }
  std::vector<double> truth(model.chain_start.size());
  for (size_t c = 0; c < truth.size(); ++c) truth[c] = scale * model.chain_start[c];
  std::string steps(model.reduction.size(), '\0');
  for (size_t i = 0; i < model.reduction.size(); ++i) {
    const uint32_t c = model.chain[i];
    truth[c] -= scale * model.reduction[i];
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

double DistortionEstimates::Estimate(const std::vector<double>& current) const {
  double d = base;
  for (double e : current) d += e;
  return d;
}

DistortionEstimates ReadDistortionIndex(const proto::StreamHeader& header,
                                        std::span<const uint32_t> chain_of) {
  const proto::PacketIndex& index = header.packets();
  DistortionEstimates out;
  out.base = header.base_distortion();
  for (float e : index.chain_distortion()) out.chain_start.push_back(e);
  std::vector<double> current = out.chain_start;
  const std::string& steps = index.distortion_step();
  out.chain.assign(chain_of.begin(), chain_of.end());
  out.after.assign(chain_of.size(), 0.0);
  out.reduction.assign(chain_of.size(), 0.0);
  for (size_t i = 0; i < chain_of.size() && i < steps.size(); ++i) {
    const uint32_t c = chain_of[i];
    if (c >= current.size()) continue;
    const int d = static_cast<uint8_t>(steps[i]);
    const double next = d == 255 ? 0.0 : current[c] * std::exp2(-d / kDistortionCodesPerOctave);
    out.reduction[i] = current[c] - next;
    out.after[i] = next;
    current[c] = next;
  }
  return out;
}

Status ValidateCompactIndex(const proto::StreamHeader& header, int packet_count,
                            int chains) {
  const proto::PacketIndex& index = header.packets();
  if (index.length_size() != packet_count) {
    return ParseError("header: " + std::to_string(index.length_size()) +
                      " packet lengths, " + std::to_string(packet_count) +
                      " packets expected from the quantizers");
  }
  if (index.check().size() != 2 * static_cast<size_t>(packet_count) ||
      index.distortion_step().size() != static_cast<size_t>(packet_count)) {
    return ParseError("header: packet index arrays differ in length");
  }
  if (index.chain_distortion_size() != chains) {
    return ParseError("header: " + std::to_string(index.chain_distortion_size()) +
                      " chain distortions, " + std::to_string(chains) + " expected");
  }
  for (float e : index.chain_distortion()) {
    if (!(e >= 0) || !std::isfinite(e)) return ParseError("header: a chain distortion is out of range");
  }
  if (!(header.base_distortion() >= 0) || !std::isfinite(header.base_distortion())) {
    return ParseError("header: base distortion out of range");
  }
  return Status::Ok();
}

}  // namespace meshwave
