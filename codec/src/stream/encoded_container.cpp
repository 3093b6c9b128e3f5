#include <vector>

#include "meshwave/container.h"
#include "meshwave/encoder.h"

namespace meshwave {

std::string SerializeContainer(const EncodedStream& stream,
                               std::span<const uint32_t> ids) {
  std::string out = SerializeContainerHead(stream.header, ids);
  for (uint32_t id : ids) out += stream.packets[id];
  return out;
}

std::string SerializeFullContainer(const EncodedStream& stream) {
  std::vector<uint32_t> ids(stream.packets.size());
  for (uint32_t i = 0; i < ids.size(); ++i) ids[i] = i;
  return SerializeContainer(stream, ids);
}

}  // namespace meshwave
