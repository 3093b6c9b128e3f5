#include "stream_splitter.h"

#include <algorithm>

#include "header_limit.h"
#include "meshwave/container.h"

namespace meshwave::client {
namespace {

constexpr size_t kPreambleBytes = 8;  // "MWV1" and the header length

uint64_t HeaderLength(std::string_view preamble) {
  uint32_t v = 0;
  for (int i = 7; i >= 4; --i) v = (v << 8) | static_cast<uint8_t>(preamble[i]);
  return v;
}

}  // namespace

Status StreamSplitter::Feed(std::string_view bytes) {
  pending_.append(bytes);
  const std::string_view all(pending_);
  size_t pos = 0;
  Status status;
  while (status.ok()) {
    const std::string_view rest = all.substr(pos);
    if (expect_header_) {
      if (rest.size() < kPreambleBytes) break;
      // ParseContainer checks the magic, the length limit, the version and
      // the header; we only need the length to know when it is complete.
      const uint64_t header_length = HeaderLength(rest);
      status = CheckHeaderLength(header_length, max_header_bytes_);
      if (!status.ok()) break;
      const uint64_t head = kPreambleBytes + header_length;
      auto parsed =
          ParseContainer(rest.substr(0, std::min<uint64_t>(rest.size(), head)),
                         /*allow_truncated=*/true);
      if (!parsed.ok()) {
        if (parsed.status().code() == StatusCode::kNeedMoreInput) break;
        status = parsed.status();
        break;
      }
      expect_header_ = false;
      pos += head;
      status = events_.OnHeader(parsed->header);
      continue;
    }
    const std::optional<uint64_t> length = events_.NextPacketLength();
    if (!length) {
      if (!rest.empty()) {
        status = ParseError(
            std::to_string(rest.size()) +
            " unexpected bytes after the last packet of the response");
      }
      break;
    }
    if (rest.size() < *length) break;
    status = events_.OnPacket(rest.substr(0, *length));
    pos += *length;
  }
  pending_.erase(0, pos);
  return status;
}

Status StreamSplitter::Finish() const {
  if (expect_header_)
    return ParseError("the response ended inside the container header");
  if (!pending_.empty()) {
    return ParseError("the response ended inside a packet (" +
                      std::to_string(pending_.size()) +
                      " bytes of it received)");
  }
  return Status::Ok();
}

}  // namespace meshwave::client
