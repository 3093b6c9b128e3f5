#include "stream_splitter.h"

#include <algorithm>

#include "header_limit.h"
#include "meshwave/container.h"

namespace meshwave::client {
Status StreamSplitter::Feed(std::string_view bytes) {
  pending_.append(bytes);
  const std::string_view all(pending_);
  size_t pos = 0;
  Status status;
  while (status.ok()) {
    const std::string_view rest = all.substr(pos);
    if (expect_header_) {
      if (rest.size() < kContainerPreambleBytes) break;
      // The length says when the header is complete; ParseContainer then
      // checks the format's length limit, the version and the header.
      const Result<uint32_t> header_length = ReadContainerHeaderLength(rest);
      status = header_length.ok() ? CheckHeaderLength(*header_length, max_header_bytes_)
                                  : header_length.status();
      if (!status.ok()) break;
      const uint64_t head = kContainerPreambleBytes + uint64_t{*header_length};
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
