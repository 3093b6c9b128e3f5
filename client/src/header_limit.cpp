#include "header_limit.h"

#include <limits>
#include <string>

namespace meshwave::client {
namespace {

// A Selection is five varints and a StreamStart two length prefixes and
// tags: well under this.
constexpr uint64_t kHeaderMessageSlack = 256;

}  // namespace

Status CheckHeaderLength(uint64_t header_bytes, uint64_t limit) {
  if (header_bytes <= limit) return Status::Ok();
  return ParseError("the server's stream header is " +
                    std::to_string(header_bytes) +
                    " bytes, over this client's limit of " +
                    std::to_string(limit) + " (--max-header)");
}

uint64_t HeaderMessageLimit(uint64_t limit) {
  return limit > std::numeric_limits<uint64_t>::max() - kHeaderMessageSlack
             ? std::numeric_limits<uint64_t>::max()
             : limit + kHeaderMessageSlack;
}

Status HeaderMessageTooLarge(uint64_t limit) {
  return ParseError("the server's stream header message is over " +
                    std::to_string(HeaderMessageLimit(limit)) +
                    " bytes, so its header is over this client's limit of " +
                    std::to_string(limit) +
                    " (--max-header); refused before reading it");
}

}  // namespace meshwave::client
