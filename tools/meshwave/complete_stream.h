// A complete .mwv stream held in memory with what the region orders need:
// every payload by id, the precincts, each split packet's part lengths, and
// the complete decode's finest positions (`region-rd`, `view-rd`).
#ifndef MESHWAVE_TOOLS_MESHWAVE_COMPLETE_STREAM_H_
#define MESHWAVE_TOOLS_MESHWAVE_COMPLETE_STREAM_H_

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "meshwave/container.h"
#include "meshwave/held_units.h"
#include "meshwave/progressive_decoder.h"
#include "meshwave/region_order.h"

namespace meshwave::cli {

struct CompleteStream {
  std::string bytes;  // the file; `container` and `payload` view into it
  ParsedContainer container;
  std::vector<std::string_view> payload;  // by id
  std::unique_ptr<StreamPrecincts> precincts;
  std::unique_ptr<HeldUnits> units;  // none held: for PacketParts
  std::vector<std::vector<uint32_t>> part_lengths;
  std::vector<Vec3> full;
  std::vector<Face> faces;
  double diagonal = 0;

  const StreamHeader& header() const { return container.header; }
  uint64_t UnitBytes(const StreamUnit& u) const {
    return u.whole() ? payload[u.id].size() : part_lengths[u.id][u.part];
  }
  // Hands `u` to the decoder (a part cut from its packet's payload).
  Status Send(ProgressiveDecoder& d, const StreamUnit& u) const;
};

// Reads `path`; InvalidArgument naming `command` when the file does not
// hold every packet.
Result<std::unique_ptr<CompleteStream>> LoadCompleteStream(
    const std::string& path, const std::string& command);

}  // namespace meshwave::cli

#endif  // MESHWAVE_TOOLS_MESHWAVE_COMPLETE_STREAM_H_
