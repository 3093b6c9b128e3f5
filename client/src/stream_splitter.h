// StreamSplitter: cuts the body of a /stream response into packets as its
// bytes arrive, whatever the pieces' sizes. The body is either a container
// (preamble and header first, parsed with ParseContainer) or payloads back
// to back; the lengths come from the owner, who knows the order.
#ifndef MESHWAVE_CLIENT_STREAM_SPLITTER_H_
#define MESHWAVE_CLIENT_STREAM_SPLITTER_H_

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "meshwave/status.h"
#include "meshwave/stream_header.h"

namespace meshwave::client {

class StreamSplitter {
 public:
  class Events {
   public:
    virtual ~Events() = default;
    virtual Status OnHeader(const StreamHeader& header) = 0;
    // Payload length of the next packet expected; nullopt when no more are.
    virtual std::optional<uint64_t> NextPacketLength() = 0;
    virtual Status OnPacket(std::string_view payload) = 0;
  };

  // `max_header_bytes`: a container whose header length field claims more
  // is refused at once, before its header is buffered (CheckHeaderLength).
  StreamSplitter(bool container, uint64_t max_header_bytes, Events& events)
      : expect_header_(container),
        max_header_bytes_(max_header_bytes),
        events_(events) {}

  // Consumes `bytes`; an error from the events, a container that does not
  // parse or bytes beyond the last expected packet stop it.
  Status Feed(std::string_view bytes);
  // At the end of the body: an error if a header or packet is incomplete.
  Status Finish() const;

 private:
  bool expect_header_;
  uint64_t max_header_bytes_;
  Events& events_;
  std::string pending_;
};

}  // namespace meshwave::client

#endif  // MESHWAVE_CLIENT_STREAM_SPLITTER_H_
