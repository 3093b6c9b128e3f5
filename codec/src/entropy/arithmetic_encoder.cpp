#include "entropy/arithmetic_encoder.h"

#include <cassert>
#include <utility>

namespace meshwave {

void ArithmeticEncoder::EncodeBits(uint32_t value, int count) {
  assert(count >= 0 && count <= 32);
  for (int i = count - 1; i >= 0; --i) EncodeBypass((value >> i) & 1);
}

void ArithmeticEncoder::ShiftLow() {
  ++shifts_;
  const uint32_t top = static_cast<uint32_t>(low_ >> 24);  // carry + 8 bits
  if (top == 0xFF) {
    // A later carry could still ripple through this byte: keep it pending.
    ++pending_ff_;
  } else {
    const uint8_t carry = static_cast<uint8_t>(top >> 8);
    // The code value stays below 1.0, so nothing carries into the byte in
    // front of the first one (the always-zero byte that is never written),
    // and the held byte never overflows: after a carry the interval lies
    // below the next multiple of the window.
    assert(has_held_ || carry == 0);
    assert(held_ + carry <= 0xFF);
    if (has_held_) out_.push_back(static_cast<char>(held_ + carry));
    out_.append(pending_ff_, static_cast<char>(carry != 0 ? 0x00 : 0xFF));
    pending_ff_ = 0;
    held_ = static_cast<uint8_t>(top);
    has_held_ = true;
  }
  low_ = (low_ & 0x00FFFFFF) << 8;
}

std::string ArithmeticEncoder::Finish() {
  const size_t shifts = shifts_;
  // The shortest value in [low, low + range): a multiple of 2^32 (all window
  // bytes zero) if there is one, else a multiple of 2^24, which always exists
  // because range >= 2^24. Shifting out one byte more than the value's
  // significant window bytes releases held_ and the pending 0xFF run; the
  // byte then held is zero and is left to the decoder's padding.
  constexpr uint64_t kMask32 = 0xFFFFFFFF;
  constexpr uint64_t kMask24 = 0x00FFFFFF;
  uint64_t value = (low_ + kMask32) & ~kMask32;
  int shift_outs = 1;
  if (value >= low_ + range_) {
    value = (low_ + kMask24) & ~kMask24;
    shift_outs = 2;
  }
  assert(value >= low_ && value < low_ + range_);
  low_ = value;
  for (int i = 0; i < shift_outs; ++i) ShiftLow();
  assert(pending_ff_ == 0 && held_ == 0);

  // The decoder of exactly these symbols reads kCodeBytes + shifts bytes;
  // each stripped trailing zero becomes one more padding byte for it.
  const size_t min_size = shifts + kCodeBytes > kMaxPaddingBytes
                              ? shifts + kCodeBytes - kMaxPaddingBytes
                              : 0;
  while (out_.size() > min_size && out_.back() == '\0') out_.pop_back();

  std::string packet = std::move(out_);
  *this = ArithmeticEncoder();
  return packet;
}

}  // namespace meshwave
