// Fuzz target: the client's StreamSplitter, which cuts an HTTP /stream body
// (a container: preamble, header, then payloads) into packets as pieces
// arrive. Input: one byte that seeds the piece sizes, then the body. The
// body is fed twice, whole and in pieces of 1-64 bytes; the splitter must
// hand the same header and packets either way, stop at the same point,
// refuse a header length field over the limit without buffering the header,
// and hand out exactly the body's bytes.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "fuzz_fixture_testonly.h"
#include "meshwave/container.h"
#include "meshwave/progression.h"
#include "stream_splitter.h"

using namespace meshwave;

namespace {

constexpr uint64_t kMaxHeader = 4096;
constexpr size_t kMaxPackets =
    64;  // of the order: enough to cover the splitting

class Recorder final : public client::StreamSplitter::Events {
 public:
  Status OnHeader(const StreamHeader& header) override {
    ++headers;
    // As the Session does (ProgressiveDecoder::Create) before it computes
    // an order: PacketOrder's precondition.
    MW_RETURN_IF_ERROR(ValidateStreamHeader(header));
    const auto order = PacketOrder(header, Progression::kQuality, -1);
    for (size_t i = 0; i < order.size() && i < kMaxPackets; ++i) {
      lengths.push_back(PacketLength(header, order[i]));
    }
    return Status::Ok();
  }
  std::optional<uint64_t> NextPacketLength() override {
    if (packets.size() >= lengths.size()) return std::nullopt;
    return lengths[packets.size()];
  }
  Status OnPacket(std::string_view payload) override {
    fuzz::Require(payload.size() == lengths[packets.size()],
                  "a packet has the announced length");
    packets.emplace_back(payload);
    return Status::Ok();
  }

  int headers = 0;
  std::vector<uint64_t> lengths;
  std::vector<std::string> packets;
  bool failed = false;
};

// Feeds `body` in pieces from `sizes` (empty: whole), then Finish.
void Run(std::string_view body, uint8_t seed, bool whole, Recorder& r) {
  client::StreamSplitter splitter(/*container=*/true, kMaxHeader, r);
  uint32_t state = seed * 2654435761u + 1;
  size_t pos = 0;
  while (pos < body.size()) {
    state = state * 1103515245u + 12345u;
    const size_t n = whole ? body.size() : 1 + (state >> 16) % 64;
    const Status s = splitter.Feed(body.substr(pos, n));
    pos += std::min(n, body.size() - pos);
    if (!s.ok()) {
      fuzz::Require(!s.message().empty(), "a refusal says why");
      r.failed = true;
      return;
    }
  }
  const Status s = splitter.Finish();
  r.failed = !s.ok();
  if (!s.ok()) fuzz::Require(!s.message().empty(), "a refusal says why");
}

uint64_t LengthField(std::string_view body) {
  uint64_t v = 0;
  for (int i = 7; i >= 4; --i)
    v = (v << 8) | static_cast<uint8_t>(body[static_cast<size_t>(i)]);
  return v;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const std::string_view body(reinterpret_cast<const char*>(data) + 1,
                              size - 1);
  Recorder whole, pieces;
  Run(body, data[0], true, whole);
  Run(body, data[0], false, pieces);
  fuzz::Require(whole.headers == pieces.headers,
                "the header does not depend on the pieces");
  fuzz::Require(whole.packets == pieces.packets,
                "the packets do not depend on the pieces");
  fuzz::Require(whole.failed == pieces.failed,
                "the outcome does not depend on the pieces");
  fuzz::Require(whole.headers <= 1, "one header at most");
  if (whole.headers == 1) {
    const uint64_t header_length = LengthField(body);
    fuzz::Require(header_length <= kMaxHeader,
                  "a header over the limit is refused");
    std::string expected;
    size_t offset = 8 + header_length;
    for (const auto& p : whole.packets) {
      fuzz::Require(body.substr(offset, p.size()) == p,
                    "packets are the body's bytes in order");
      offset += p.size();
    }
    if (!whole.failed)
      fuzz::Require(offset == body.size(), "a clean finish consumed the body");
  }
  return 0;
}
