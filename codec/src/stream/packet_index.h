// The compact packet index (docs/FORMAT.md 2.1): what a reader derives from
// the header instead of storing per packet (subband, bitplane), the 16-bit
// payload check, and the distortion estimates coded in one byte per packet.
//
// Distortion model. The packets form chains: in a 3xC or SIM stream the
// packets of one subband (j, B_j) ... (j, 0), which the dependencies force
// to arrive in that order, and chain J, the base refinement's planes (the
// PGC measurement coder, pgc/, makes all its packets one chain). The
// estimated distortion of a decoder holding some packets is
//   base_distortion + sum over chains of E_c(last packet of c held),
// with E_c(none) = chain_distortion[c]. Every term is positive, so a coarse
// code of each term gives a small relative error of the sum (no
// cancellation of large numbers, as differences of reductions would give).
// Per packet one byte d: E(packet) = E(previous in the chain) * 2^(-d/32),
// quantised in closed loop by the encoder so errors do not accumulate.
#ifndef MESHWAVE_STREAM_PACKET_INDEX_H_
#define MESHWAVE_STREAM_PACKET_INDEX_H_

#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "meshwave/status.h"
#include "meshwave/stream_header.h"

namespace meshwave {

// Steps of the per-packet distortion code per octave.
inline constexpr double kDistortionCodesPerOctave = 32;

// CRC-16/CCITT-FALSE (polynomial 0x1021, init 0xFFFF, no reflection, no
// final xor) of a payload: every burst of up to 16 bits, every odd number
// of bit errors and every 2- or 3-bit error in a payload up to 4 KB is
// caught; random damage slips through with probability 2^-16.
uint16_t PacketCheck(std::string_view payload);
// Whether `payload` matches packet `id`'s check in the index (the index
// must have passed validation: 2 check bytes per packet).
bool PacketCheckMatches(const StreamHeader::PacketIndex& index, uint32_t id,
                        std::string_view payload);

// Packet ids <-> (subband, bitplane), from the quantizers' top bitplanes:
// ids run subband by subband, bitplanes descending, then the base
// refinement's packets, planes descending, then each channel's packets
// as the geometry's, channel by channel, then each texture map's levels,
// coarsest first, map by map (FORMAT.md 2.1, 2.3, 2.4).
class PacketLayout {
 public:
  explicit PacketLayout(const StreamHeader& h);
  // Id of packet (j, b), -1 when it does not exist.
  int Id(int j, int b) const;
  // Id of the base refinement packet of `plane`, -1 when it does not exist.
  int BaseId(int plane) const;
  // Id of packet (j, b) of channel k, -1 when it does not exist.
  int ChannelId(int k, int j, int b) const;
  int Top(int j) const { return top_[static_cast<size_t>(j)]; }
  int ChannelTop(int k, int j) const {
    return channel_top_[static_cast<size_t>(k)][static_cast<size_t>(j)];
  }
  int channels() const { return static_cast<int>(channel_top_.size()); }
  // The channel packet `id` belongs to; -1 for the geometry's packets (its
  // subbands' and the base refinement's).
  int Channel(uint32_t id) const {
    return id < channel_.size() ? channel_[id] : -1;
  }
  bool IsChannel(uint32_t id) const { return Channel(id) >= 0; }
  // The texture map packet `id` is a level of; -1 for every other packet.
  int TextureMap(uint32_t id) const {
    return id < texture_.size() ? texture_[id] : -1;
  }
  bool IsTexture(uint32_t id) const { return TextureMap(id) >= 0; }
  int texture_maps() const { return static_cast<int>(texture_levels_.size()); }
  int TextureLevels(int map) const { return texture_levels_[static_cast<size_t>(map)]; }
  // Id of level `level` of texture map `map`, -1 when it does not exist.
  int TextureId(int map, int level) const;
  // The original layer (FORMAT.md 2.5): its connectivity packet (part 0),
  // then its positions, coarse (part 1) to finest; they follow every other
  // packet. Part of `id` in it, -1 for every other packet.
  int OriginalPart(uint32_t id) const {
    return id >= static_cast<uint32_t>(original_first_) && id < static_cast<uint32_t>(count_)
               ? static_cast<int>(id) - original_first_
               : -1;
  }
  bool IsOriginal(uint32_t id) const { return OriginalPart(id) >= 0; }
  // The id of the layer's first part (count() without a layer), its number
  // of packets (0 without one) and the id of part `part` (-1 when it does
  // not exist).
  int original_first() const { return original_first_; }
  int original_parts() const { return count_ - original_first_; }
  int OriginalId(int part) const {
    return part >= 0 && part < original_parts() ? original_first_ + part : -1;
  }
  // Whether detail packet `id` holds one codeword per precinct behind a
  // table of their lengths (PacketIndex.split_planes).
  bool IsSplit(uint32_t id) const {
    if (id >= static_cast<uint32_t>(detail_count_)) return false;
    const size_t j = static_cast<size_t>(subband_[id]);
    return j < split_planes_.size() && static_cast<uint32_t>(Bitplane(id)) < split_planes_[j];
  }
  int levels() const { return static_cast<int>(top_.size()); }
  int count() const { return count_; }
  int detail_count() const { return detail_count_; }
  int base_planes() const { return base_planes_; }
  bool IsBase(uint32_t id) const {
    return id >= static_cast<uint32_t>(detail_count_) &&
           id < static_cast<uint32_t>(detail_count_ + base_planes_);
  }
  // The subband (-1 for a base refinement or texture packet; a channel
  // packet's subband of its channel) and bitplane (the base refinement's
  // plane, a texture packet's level) of packet `id` (0 <= id < count()).
  int Subband(uint32_t id) const { return subband_[id]; }
  int Bitplane(uint32_t id) const;
  // The packets `id` needs first (PacketDependencies): the one above it in
  // its subband (or in the base refinement) and, with parent contexts
  // (3xC), the parent subband's at the same bitplane, both of its own
  // signal (the geometry or its channel). Empty for a texture packet (a
  // whole image) and an id out of range. At most two, so no allocation: the decoder asks for every
  // packet it is offered.
  struct Needs {
    std::array<uint32_t, 2> ids{};
    int count = 0;
    const uint32_t* begin() const { return ids.data(); }
    const uint32_t* end() const { return ids.data() + count; }
  };
  Needs Dependencies(uint32_t id, bool parent_contexts) const;

 private:
  std::vector<int> first_;  // id of (j, top_j)
  std::vector<int> top_;
  std::vector<std::vector<int>> channel_first_;  // per channel, as first_
  std::vector<std::vector<int>> channel_top_;
  std::vector<int> subband_;  // per id; -1 for the base refinement's
  std::vector<int> channel_;  // per id; -1 for the geometry's
  std::vector<int> texture_;  // per id; -1 but for texture packets
  std::vector<int> texture_first_, texture_levels_;  // per map
  std::vector<uint32_t> split_planes_;  // per subband, as in the header
  int detail_count_ = 0;
  int base_planes_ = 0;
  int original_first_ = 0;  // == count_ without an original layer
  int count_ = 0;
};

// Every order ends with the original layer's packets, parts in order
// (FORMAT.md 7): after the semi-regular stream, so a client stops at the
// remesh or goes on to the exact mesh. Orders limited to fewer than all
// `map.levels()` levels (`used_levels`) leave it out.
inline void AppendOriginalLayer(const PacketLayout& map, int used_levels,
                                std::vector<uint32_t>& order) {
  if (used_levels < map.levels()) return;
  for (int part = 0; part < map.original_parts(); ++part) {
    order.push_back(static_cast<uint32_t>(map.OriginalId(part)));
  }
}

// The estimates a reader derives from a validated header. For any set of
// packets closed under the dependencies the estimate is base + the sum over
// chains of the chain's term after its last packet held (chain_start when
// none): Estimate() sums in chain order, so the figure does not depend on
// the order the packets arrived in. reduction = term before - term after.
struct DistortionEstimates {
  double base = 0;
  // The chains of the geometry, which Estimate sums: the first ones, the
  // channels' and the texture maps' chains following them.
  size_t geometry_chains = 0;
  // The original layer's chain (FORMAT.md 2.5), -1 without one: once its
  // coarse positions are held its term is the estimate (ShownEstimate).
  int original_chain = -1;
  std::vector<double> chain_start;  // per chain
  std::vector<uint32_t> chain;      // per packet
  std::vector<double> after;        // per packet: its chain's term after it
  std::vector<double> reduction;    // per packet
  double start() const { return Estimate(chain_start); }
  // The geometry's estimated error. `current`: every chain's term
  // (chain_start, or `after` of its last packet).
  double Estimate(const std::vector<double>& current) const;
  // The estimate of the mesh a decoder shows: the original layer's term
  // once `original_ready`, else Estimate.
  double ShownEstimate(const std::vector<double>& current, bool original_ready) const {
    return original_ready && original_chain >= 0 &&
                   static_cast<size_t>(original_chain) < current.size()
               ? current[static_cast<size_t>(original_chain)]
               : Estimate(current);
  }
};
DistortionEstimates ReadDistortionIndex(const StreamHeader& header,
                                        std::span<const uint32_t> chain_of);
// The chain of each packet: its subband (3xC and SIM), J for the base
// refinement's packets, J + 1 + k J + j for subband j of channel k, then
// J + 1 + K J + m for texture map m (K channels), and after them one for
// the original layer (FORMAT.md 2.5).
std::vector<uint32_t> PacketChains(const StreamHeader& header);
// How many chains a header's packets form (the count PacketChains uses).
size_t ChainCount(const StreamHeader& header);

// The estimated PSNR rule, the one ProgressiveDecoder::EstimatedPsnr and
// EstimatedPsnrCurve share: dB with the bounding-box diagonal of the header
// (HeaderDiagonal, meshwave/stream_header.h) as peak, from an estimated
// squared error summed over the header's vertices; +infinity when no error
// is left.
double EstimatedPsnrFromDistortion(const StreamHeader& header, double diagonal,
                                   double distortion);

// Shape checks of the compact fields against `packet_count` packets.
Status ValidateCompactIndex(const StreamHeader& header, int packet_count,
                            int chains);

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_PACKET_INDEX_H_
