#include "entropy/arithmetic_decoder.h"

#include <cassert>

namespace meshwave {

ArithmeticDecoder::ArithmeticDecoder(std::span<const uint8_t> packet)
    : next_(packet.data()), end_(packet.data() + packet.size()) {
  for (int i = 0; i < kCodeBytes; ++i) code_ = (code_ << 8) | NextByte();
}

ArithmeticDecoder::ArithmeticDecoder(std::string_view packet)
    // Viewing char bytes as unsigned char is allowed by the aliasing rules.
    : ArithmeticDecoder(std::span<const uint8_t>(
          reinterpret_cast<const uint8_t*>(packet.data()), packet.size())) {}

uint32_t ArithmeticDecoder::DecodeBits(int count) {
  assert(count >= 0 && count <= 32);
  uint32_t value = 0;
  for (int i = 0; i < count; ++i) {
    value = (value << 1) | static_cast<uint32_t>(DecodeBypass());
  }
  return value;
}

}  // namespace meshwave
