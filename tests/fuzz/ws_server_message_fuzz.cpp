// Fuzz target: the client's parser of the WebSocket server's messages
// (ServerMessageReader), a whole answer at a time. Input: a flags byte
// (bit 0: the request was a start, so a header is expected; bit 1: the
// message came in a text frame), then messages, each a 2-byte little-endian
// length and its bytes. The reader must refuse any message out of order,
// hand the sink a head before anything else and a header only after a
// start, stop at Done, and enforce its size limit with a message a person
// can act on.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "fuzz_fixture_testonly.h"
#include "header_limit.h"
#include "ws_server_messages.h"

using namespace meshwave;

namespace {

constexpr uint64_t kMaxHeader = 512;
constexpr uint64_t kPacketLimit = 4096;

class CheckingSink final : public client::StreamSink {
 public:
  explicit CheckingSink(bool expect_header) : expect_header_(expect_header) {}
  Status OnHead(const client::StreamHead& head) override {
    fuzz::Require(heads == 0, "one head per answer");
    fuzz::Require(head.next_cursor >= head.packets || head.packets == 0,
                  "a head is consistent");
    ++heads;
    return Status::Ok();
  }
  Status OnBytes(std::string_view) override {
    fuzz::Require(false, "a message transport never hands raw bytes");
    return Status::Ok();
  }
  Status OnHeaderMessage(std::string_view header) override {
    fuzz::Require(expect_header_, "a header only after a start");
    fuzz::Require(heads == 1 && headers == 0 && packets == 0,
                  "the header comes right after the head");
    fuzz::Require(header.size() <= client::HeaderMessageLimit(kMaxHeader),
                  "the header fits its limit");
    ++headers;
    return Status::Ok();
  }
  Status OnPacketMessage(size_t, uint32_t, std::string_view payload) override {
    fuzz::Require(heads == 1, "packets only after the head");
    fuzz::Require(payload.size() <= kPacketLimit, "a packet fits its limit");
    ++packets;
    return Status::Ok();
  }
  int heads = 0, headers = 0, packets = 0;

 private:
  bool expect_header_;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const bool expect_header = (data[0] & 1) != 0;
  const bool binary = (data[0] & 2) == 0;
  CheckingSink sink(expect_header);
  client::ServerMessageReader reader(expect_header, kMaxHeader, sink, "fuzz");
  size_t pos = 1;
  while (pos + 2 <= size) {
    const size_t length = data[pos] | static_cast<size_t>(data[pos + 1]) << 8;
    pos += 2;
    if (length > size - pos) break;
    // What the transport does: a frame over the limit is refused unread.
    if (length > reader.NextMessageLimit(kPacketLimit)) {
      const Status s = reader.TooLarge(kPacketLimit);
      fuzz::Require(!s.ok() && !s.message().empty(),
                    "an oversize message is refused with a reason");
      break;
    }
    auto r = reader.OnMessage(
        std::string_view(reinterpret_cast<const char*>(data) + pos, length),
        binary);
    pos += length;
    if (!r.ok()) {
      fuzz::Require(!r.status().message().empty(), "a refusal says why");
      break;
    }
    if (r->has_value()) {
      fuzz::Require(sink.heads == 1, "Done only after a selection");
      fuzz::Require(!expect_header || sink.headers == 1,
                    "a start's answer had its header");
      break;
    }
    fuzz::Require(binary, "a text message is refused");
  }
  return 0;
}
