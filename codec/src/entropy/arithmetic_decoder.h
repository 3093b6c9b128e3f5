// ArithmeticDecoder: reads the binary symbols of one packet written by
// ArithmeticEncoder (byte format in entropy/context_model.h).
#ifndef MESHWAVE_ENTROPY_ARITHMETIC_DECODER_H_
#define MESHWAVE_ENTROPY_ARITHMETIC_DECODER_H_

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "entropy/context_model.h"

namespace meshwave {

// Decodes symbols from exactly one packet. Safe on untrusted bytes: it
// never reads outside `packet` (reads past the end yield 0x00 and are
// counted), never fails and never loops; corrupt input just decodes to other
// symbols. The caller drives it by its own symbol count and checks overrun()
// after the last symbol. The bytes must outlive the decoder.
class ArithmeticDecoder {
 public:
  explicit ArithmeticDecoder(std::span<const uint8_t> packet);
  // The same over a std::string's bytes (e.g. a protobuf `bytes` field).
  explicit ArithmeticDecoder(std::string_view packet);

  // Decodes one symbol with the probability in `ctx`, then updates `ctx`.
  // Returns 0 or 1.
  int Decode(BinaryContext& ctx) {
    const uint32_t bound = static_cast<uint32_t>(
        (uint64_t{range_} * ctx.probability()) >> kProbBits);
    int bit;
    if (code_ < bound) {
      range_ = bound;
      bit = 0;
    } else {
      code_ -= bound;
      range_ -= bound;
      bit = 1;
    }
    ctx.Update(bit);
    Normalize();
    return bit;
  }

  // Decode, without a branch on the symbol: for symbols a branch predictor
  // cannot guess (signs, refinement bits: about 1 in 2 each), where a
  // mispredicted branch costs more than computing both outcomes. Same
  // result, same state as Decode.
  int DecodeUnpredictable(BinaryContext& ctx) {
    const uint32_t bound = static_cast<uint32_t>(
        (uint64_t{range_} * ctx.probability()) >> kProbBits);
    const uint32_t bit = code_ >= bound ? 1u : 0u;
    const uint32_t mask = 0u - bit;  // all ones for 1
    code_ -= bound & mask;
    range_ = (bound & ~mask) | ((range_ - bound) & mask);
    ctx.UpdateUnpredictable(bit);
    Normalize();
    return static_cast<int>(bit);
  }

  // Decodes one symbol coded at probability 1/2. Returns 0 or 1.
  int DecodeBypass() {
    const uint32_t bound = range_ >> 1;
    int bit;
    if (code_ < bound) {
      range_ = bound;
      bit = 0;
    } else {
      code_ -= bound;
      range_ -= bound;
      bit = 1;
    }
    Normalize();
    return bit;
  }

  // Decodes `count` bypass symbols, most significant first; `count` is in
  // [0, 32]. The result is below 2^count.
  uint32_t DecodeBits(int count);

  // Bytes read past the end of the packet so far (each read as 0x00).
  size_t padding_bytes() const { return padding_bytes_; }

  // True when more padding was read than any packet ArithmeticEncoder wrote
  // needs for its own symbols (kMaxPaddingBytes): the caller decoded more
  // symbols than were encoded, or the packet is truncated or corrupt. False
  // does not prove the packet intact (the container's CRC does that).
  bool overrun() const { return padding_bytes_ > kMaxPaddingBytes; }

 private:
  uint8_t NextByte() {
    if (next_ != end_) return *next_++;
    ++padding_bytes_;
    return 0;
  }

  void Normalize() {
    while (range_ < kRangeTop) {
      range_ <<= 8;
      code_ = (code_ << 8) | NextByte();
    }
  }

  const uint8_t* next_;
  const uint8_t* end_;
  uint32_t code_ = 0;
  uint32_t range_ = 0xFFFFFFFF;
  size_t padding_bytes_ = 0;
};

}  // namespace meshwave

#endif  // MESHWAVE_ENTROPY_ARITHMETIC_DECODER_H_
