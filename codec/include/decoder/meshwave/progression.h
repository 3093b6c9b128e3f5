// Orders in which a stream's packets can be sent, and the longest prefix of
// an order that fits a byte budget. Every prefix of every order is closed
// under the packet dependencies, so it decodes.
#ifndef MESHWAVE_PROGRESSION_H_
#define MESHWAVE_PROGRESSION_H_

#include <cstdint>
#include <string>
#include <vector>

#include "meshwave/status.h"
#include "meshwave/stream_header.h"

namespace meshwave {

enum class Progression {
  // Bitplane-major, coarse subbands first within a bitplane; each base
  // refinement plane just before the details' bitplane of its step
  // (BaseQualityShift).
  kQuality,
  // Subband-major: the base refinement, all bitplanes of d^0, then d^1, ...
  kResolution,
  kRd,          // greedy by distortion reduction per byte
};
Result<Progression> ParseProgression(const std::string& name);
const char* ProgressionName(Progression p);

// The packets (ids into the header's index) of subbands below max_level
// (-1: all) in the given order. The header must have passed validation
// (ProgressiveDecoder::Create or ValidateStreamHeader). Texture levels
// (format version 9) go where docs/FORMAT.md 7 places them: by value per
// byte among the others (quality, rd), after the subband of their
// resolution (resolution); those matching a mesh level above max_level are
// left out.
std::vector<uint32_t> PacketOrder(const StreamHeader& header,
                                  Progression progression, int max_level = -1);

// The quality order sends base refinement plane b just before the details'
// bitplane b + shift, shift = floor(log2(base.step / step of subband 0's
// first component) + 0.5): where the base's finest-grid cells, 2^b of them,
// match that bitplane's step (docs/FORMAT.md 7). 0 without quantizers.
int BaseQualityShift(const StreamHeader& header);

// The packets that packet `id` needs first (at most two).
std::vector<uint32_t> PacketDependencies(const StreamHeader& header,
                                         uint32_t id);

struct Selection {
  std::vector<uint32_t> ids;  // order[cursor .. next_cursor)
  size_t next_cursor = 0;
  uint64_t bytes = 0;  // container size (cursor 0) or payload bytes
};

// The longest run of `order` starting at `cursor` that fits `budget` bytes:
// counting the whole container (header included) when cursor is 0, and the
// packets' payloads only when continuing from a cursor.
Selection SelectPackets(const StreamHeader& header,
                        const std::vector<uint32_t>& order, uint64_t budget,
                        size_t cursor = 0);

// The longest run of `order` starting at `cursor` (0 included) whose
// payloads fit `budget` bytes: for a client that already holds the header.
Selection SelectPayloads(const StreamHeader& header,
                         const std::vector<uint32_t>& order, uint64_t budget,
                         size_t cursor);

// The payload length in bytes of packet `id` (an id of the header's index;
// the header must have passed validation). Lets a client split a stream of
// concatenated payloads without reading the packet index itself.
uint64_t PacketLength(const StreamHeader& header, uint32_t id);

// Checks that an untrusted header is complete and consistent: version,
// transform, quantizers, and a packet index holding exactly the packets
// (j, b), b from the subband's top bitplane down to 0, in that order.
Status ValidateStreamHeader(const StreamHeader& header);

}  // namespace meshwave

#endif  // MESHWAVE_PROGRESSION_H_
