// Fuzz target: the original layer's positions decoder
// (original/original_positions.h) on untrusted payloads. The first bytes
// make a small traversal (every prediction kind), the shift and the grid
// extent; the rest are payloads, each behind a length byte. A payload
// taken must leave every point within the extent; once all are held the
// points must survive an encode and decode unchanged.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "fuzz_require_testonly.h"
#include "original/original_positions.h"

namespace meshwave::original::fuzz_input {

inline constexpr size_t kHeaderBytes = 6;

struct PositionsFuzzCase {
  Traversal traversal;
  int shift = 0;
  uint32_t max_coordinate = 0;
};

// Bytes: vertex count (1 + b % 64), shift, extent (3 bytes, little-endian,
// shifted up by the shift byte's high bits), order flag; then one byte per
// vertex choosing its prediction's kind and vertices among the earlier ones.
// Consumes what it reads from `bytes`.
inline PositionsFuzzCase MakeCase(std::string_view& bytes) {
  PositionsFuzzCase out;
  if (bytes.size() < kHeaderBytes) return out;
  const auto byte = [&](size_t i) { return static_cast<uint8_t>(bytes[i]); };
  const uint32_t n = 1 + byte(0) % 64;
  out.shift = byte(1) % (kMaxShift + 1);
  out.max_coordinate = (uint32_t{byte(2)} | uint32_t{byte(3)} << 8 | uint32_t{byte(4)} << 16)
                       << (byte(1) >> 4);
  const bool reversed = byte(5) & 1;
  bytes.remove_prefix(kHeaderBytes);
  for (uint32_t i = 0; i < n; ++i) out.traversal.order.push_back(reversed ? n - 1 - i : i);
  for (uint32_t i = 0; i < n; ++i) {
    const uint8_t b = i < bytes.size() ? static_cast<uint8_t>(bytes[i]) : 0;
    Prediction p;
    if (i > 0) {
      const auto earlier = [&](int bits) { return out.traversal.order[(b >> bits) % i]; };
      switch (b % 4) {
        case 0: p = {earlier(2), earlier(4), earlier(6)}; break;
        case 1: p = {earlier(2), earlier(5)}; break;
        case 2: p = {earlier(2)}; break;
        default: break;
      }
    }
    out.traversal.predictions.push_back(p);
  }
  bytes.remove_prefix(std::min<size_t>(n, bytes.size()));
  return out;
}

}  // namespace meshwave::original::fuzz_input

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace meshwave;
  using namespace meshwave::original;
  using fuzz::Require;
  std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const fuzz_input::PositionsFuzzCase c = fuzz_input::MakeCase(bytes);
  if (c.traversal.order.empty()) return 0;
  PositionsDecoder decoder(c.traversal, c.shift, c.max_coordinate);
  // Payloads behind a length byte; a length byte of 255 asks for a payload
  // out of turn.
  for (int attempts = 0; attempts < 16 && !bytes.empty(); ++attempts) {
    const uint8_t length_byte = static_cast<uint8_t>(bytes[0]);
    bytes.remove_prefix(1);
    const bool out_of_turn = length_byte == 255;
    const size_t length = std::min<size_t>(out_of_turn ? 0 : length_byte, bytes.size());
    const std::string payload(bytes.substr(0, length));
    bytes.remove_prefix(length);
    const int held = decoder.held();
    const auto before = decoder.GridPositions();
    const Status status = decoder.Add(out_of_turn ? held + 1 : held, payload);
    if (!status.ok()) {
      Require(decoder.held() == held, "a refused payload changes the count held");
      Require(decoder.GridPositions() == before, "a refused payload changes the points");
      continue;
    }
    Require(!out_of_turn, "a payload out of turn is taken");
    const auto positions = decoder.GridPositions();
    Require(positions.size() == c.traversal.order.size(), "one point per vertex");
    const double middle = ((uint32_t{1} << (c.shift - held)) - 1) / 2.0;
    for (const auto& p : positions) {
      for (double x : p) Require(x >= middle && x <= c.max_coordinate + middle, "point off the grid");
    }
  }
  if (decoder.held() == c.shift + 1) {
    std::vector<GridPoint> q;
    for (const auto& p : decoder.GridPositions()) {
      q.push_back({static_cast<uint32_t>(p[0]), static_cast<uint32_t>(p[1]),
                   static_cast<uint32_t>(p[2])});
    }
    const std::vector<std::string> again = EncodePositions(c.traversal, q, c.shift);
    PositionsDecoder check(c.traversal, c.shift, c.max_coordinate);
    for (int k = 0; k <= c.shift; ++k) Require(check.Add(k, again[k]).ok(), "re-encoded payload refused");
    Require(check.GridPositions() == decoder.GridPositions(), "round trip changes the points");
  }
  return 0;
}
