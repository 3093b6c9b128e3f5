// ArithmeticEncoder: writes one packet's binary symbols as a single
// range-coded codeword (byte format in entropy/context_model.h).
#ifndef MESHWAVE_ENTROPY_ARITHMETIC_ENCODER_H_
#define MESHWAVE_ENTROPY_ARITHMETIC_ENCODER_H_

#include <cstddef>
#include <cstdint>
#include <string>

#include "entropy/context_model.h"

namespace meshwave {

// Codes binary symbols with adaptive contexts or at probability 1/2, and
// terminates the codeword with the shortest flush the decoder's 0x00
// padding allows. Reusable: Finish() returns the packet and starts afresh.
class ArithmeticEncoder {
 public:
  // Codes `bit` (0 or 1) with the probability in `ctx`, then updates `ctx`.
  void Encode(int bit, BinaryContext& ctx) {
    const uint32_t bound = static_cast<uint32_t>(
        (uint64_t{range_} * ctx.probability()) >> kProbBits);
    if (bit == 0) {
      range_ = bound;
    } else {
      low_ += bound;
      range_ -= bound;
    }
    ctx.Update(bit);
    Normalize();
  }

  // Codes `bit` (0 or 1) at probability 1/2, e.g. for raw refinement bits.
  void EncodeBypass(int bit) {
    const uint32_t bound = range_ >> 1;
    if (bit == 0) {
      range_ = bound;
    } else {
      low_ += bound;
      range_ -= bound;
    }
    Normalize();
  }

  // Codes the low `count` bits of `value` as bypass symbols, most significant
  // first. `count` is in [0, 32]; bits above `count` are ignored.
  void EncodeBits(uint32_t value, int count);

  // Terminates the codeword and returns the packet (empty when no symbol was
  // coded). The encoder is then back in its initial state.
  std::string Finish();

 private:
  void Normalize() {
    while (range_ < kRangeTop) {
      range_ <<= 8;
      ShiftLow();
    }
  }

  // Moves the top byte of the 32-bit window of low_ out: into held_, or into
  // the run of 0xFF bytes behind it that a later carry would turn into 0x00.
  void ShiftLow();

  uint64_t low_ = 0;  // 32-bit window plus carry (bit 32)
  uint32_t range_ = 0xFFFFFFFF;
  uint8_t held_ = 0;       // last byte out, may still take a carry
  bool has_held_ = false;  // false until the first byte leaves
  size_t pending_ff_ = 0;  // 0xFF bytes after held_, not yet final
  size_t shifts_ = 0;      // normalisation shifts in this packet
  std::string out_;        // settled bytes
};

}  // namespace meshwave

#endif  // MESHWAVE_ENTROPY_ARITHMETIC_ENCODER_H_
