// What the arithmetic encoder and decoder must agree on: the adaptive
// probability state of one binary context, the coder's constants, and the
// byte format of a packet (an LZMA-style binary range coder with a minimal flush; docs/FORMAT.md).
//
// Packet byte format (one packet = one codeword; copied into docs/FORMAT.md)
// --------------------------------------------------------------------------
// A packet is a byte string B[0..n). The bytes do not mark their own end: the
// layer above knows the packet length n (container index), how many symbols
// to decode and which context each symbol uses. Every packet starts a fresh
// decoder and fresh contexts.
//
// Reading. Byte i of the code stream is B[i] for i < n and 0x00 for i >= n
// (padding; a decoder must never read the bytes that follow the packet).
//
// Decoder state: two unsigned 32-bit integers `code` and `range`.
//   Init:   range = 0xFFFFFFFF; code = the stream bytes 0..3, big-endian.
//   Normalise (after every symbol):
//           while range < 2^24: range = range << 8 (mod 2^32),
//                               code  = (code << 8 | next stream byte) mod 2^32
//   Context symbol with state (p, n) below, q = p >> 1 (15 bits, 1..32767):
//           bound = (range * q) >> 15            (exact, 64-bit product)
//           code < bound ? bit = 0, range = bound
//                        : bit = 1, code -= bound, range -= bound
//           then update the context with `bit`, then normalise.
//   Bypass symbol (probability 1/2, no context):
//           bound = range >> 1, same rule as above, then normalise.
//   Bits(count): `count` bypass symbols, most significant bit first.
//
// Context state: p = 16-bit estimate of P(bit = 0), n = symbols seen, capped.
//   Init (every packet): p = 32768, n = 0, unless the layer above names
//   another start for a context (3xC's neighbour contexts, FORMAT.md 5.3).
//   Update: r = 65535 / (min(n, 30) + 2)               (integer division)
//           bit 0: p += ((65536 - p) * r) >> 16
//           bit 1: p -= (p * r) >> 16
//           n = min(n + 1, 30)
//   r < 2^15 keeps p in [2, 65535], hence q in [1, 32767] and 0 < bound <
//   range for every range >= 2^24.
//
// Encoder, described with an unbounded integer L (init 0) next to `range`
// (init 0xFFFFFFFF) and a shift count N (init 0): a symbol takes the same
// bound as above; bit 0: range = bound; bit 1: L += bound, range -= bound;
// normalise: while range < 2^24: range <<= 8, L <<= 8, N += 1. The code value
// is V / 2^(32 + 8N) for an integer V in the final interval [L, L + range):
//   V = L rounded up to a multiple of 2^32 if that is < L + range,
//       else L rounded up to a multiple of 2^24 (always < L + range);
// the choice with the fewest significant bytes. The packet is V big-endian
// in N + 4 bytes (V < 2^(32 + 8N)) with trailing 0x00 bytes removed, but at
// least N + 4 - kMaxPaddingBytes bytes kept. Zero symbols give the empty
// packet. ArithmeticEncoder keeps only a 32-bit window of L with a carry
// bit, the last byte shifted out and a count of 0xFF bytes after it that a
// carry may still turn into 0x00 (LZMA's cache scheme); it never emits
// LZMA's always-zero byte in front of the window.
//
// Padding budget. The decoder of exactly the encoded symbols reads N + 4
// bytes, of which V's last 3 or 4 are zero; stripped zeros add to that
// padding, but never beyond kMaxPaddingBytes. So reading more padding means
// the caller decoded more symbols than were encoded, or the packet is
// truncated or corrupt. Every proper prefix of a packet either decodes other
// symbols or reads more than kMaxPaddingBytes of padding. Staying within the
// budget proves nothing (the CRC in the container index is the integrity
// check). Without the budget no padding count would be suspect: a packet of
// only 0-bits would code to zero bytes.
#ifndef MESHWAVE_ENTROPY_CONTEXT_MODEL_H_
#define MESHWAVE_ENTROPY_CONTEXT_MODEL_H_

#include <array>
#include <cstddef>
#include <cstdint>

namespace meshwave {

// Precision of the probability the coder multiplies the range by.
inline constexpr int kProbBits = 15;
// Normalisation keeps range >= 2^24, so one output byte per shift.
inline constexpr uint32_t kRangeTop = uint32_t{1} << 24;
// Bytes read at initialisation.
inline constexpr int kCodeBytes = 4;
// The most padding bytes (0x00 read past the packet end) a decoder of
// exactly the encoded symbols needs. The flush itself leaves 3 or 4; the
// rest lets the encoder strip the zeros a run of 0-bits at the end of a
// packet leaves. Measured over 3,000 packets of 1-16 contexts with P(1)
// log-uniform in [1e-3, 0.03] (mean 12 bytes), bytes per packet more than
// with unlimited stripping: cap 4 +0.14, cap 8 +0.005; with P(1) up to 0.3
// (mean 34 bytes): +0.02 and 0.
inline constexpr size_t kMaxPaddingBytes = 8;

// Context adaptation: the rate starts at 1/2 and falls as 1/(n + 2), so the
// first symbols move the estimate as a count-based estimator would (KT-like),
// then stays at 1/32 so the state follows drifting statistics.
//
// Why (evidence, not taste): ideal code length -sum log2 q of the 15-bit
// coder probability, excess over the true-p entropy in bits per context and
// packet, mean over many random streams (scratch simulation; the
// BinaryContextTest cases pin the first rows):
//
//   source                  symbols count->1/32 shift 4 shift 5 4+7 avg
//   P(0) ~ U(0,1)                30         2.1     3.0     4.4     4.6
//   P(0) ~ U(0,1)               300         5.5    10.0     8.6    11.5
//   P(0) ~ U(0,1)              3000        39.0    83.5    41.9    36.1
//   rarer P log-U[1e-3,0.5]      30         2.4     7.8    11.9    12.3
//   rarer P log-U[1e-3,0.5]     300         5.2    13.7    18.5    32.0
//   rarer P log-U[1e-3,0.5]    3000        35.2    78.8    48.6    50.9
//   new U(0,1) every 300       3000       132.7   130.0   135.8   174.4
//   skewed, new every ~500     2000       126.7   110.7   138.7   188.4
//   one symbol repeated      100000        74.4    48.7    97.3   215.5
//
// Packets hold tens to hundreds of symbols per context, where the count-based
// start cuts the learning cost of every fixed shift by 30 to 85% (LZMA's
// 11-bit shift 5 scores within 1% of the "shift 5" column). A final rate of
// 1/32 matches shift 5 on long and drifting sources; 1/128 would save ~28 bits
// at 3000 stationary symbols but cost ~210 with a new P every 300 symbols.
inline constexpr int kAdaptCountLimit = 30;

namespace entropy_internal {

// r(n) = 65535 / (n + 2), in units of 2^-16; below 1/2, see the format.
inline constexpr std::array<uint16_t, kAdaptCountLimit + 1> kAdaptRate = [] {
  std::array<uint16_t, kAdaptCountLimit + 1> rate{};
  for (int n = 0; n <= kAdaptCountLimit; ++n) {
    rate[n] = static_cast<uint16_t>(65535 / (n + 2));
  }
  return rate;
}();

}  // namespace entropy_internal

// The adaptive probability of one binary decision. Every packet starts its
// contexts in this default state; encoder and decoder update them alike.
class BinaryContext {
 public:
  constexpr BinaryContext() = default;
  // A context that starts as if it had seen `count` (<= kAdaptCountLimit)
  // symbols with P(bit == 0) = p0 / 2^16, p0 in [2, 65535].
  constexpr BinaryContext(uint16_t p0, uint8_t count) : p_(p0), count_(count) {}

  // P(bit == 0) in units of 2^-kProbBits, always in [1, 2^kProbBits - 1].
  uint32_t probability() const { return p_ >> 1; }

  // Moves the estimate towards `bit` (0 or 1).
  void Update(int bit) {
    // Most symbols meet a context past its first 30 (a packet codes
    // hundreds per context): there the rate is a constant, with no table
    // load and no count to store (a well-predicted branch).
    if (count_ == kAdaptCountLimit) [[likely]] {
      Move(bit, entropy_internal::kAdaptRate[kAdaptCountLimit]);
    } else {
      Move(bit, entropy_internal::kAdaptRate[count_]);
      ++count_;
    }
  }

  // Update for a symbol that is 0 or 1 about equally often: both moves
  // computed and one selected by mask, no branch on `bit` (0 or 1).
  void UpdateUnpredictable(uint32_t bit) {
    uint32_t rate;
    if (count_ == kAdaptCountLimit) [[likely]] {
      rate = entropy_internal::kAdaptRate[kAdaptCountLimit];
    } else {
      rate = entropy_internal::kAdaptRate[count_];
      ++count_;
    }
    const uint32_t p = p_;
    const uint32_t up = ((65536 - p) * rate) >> 16;
    const uint32_t down = (p * rate) >> 16;
    const uint32_t mask = 0u - bit;
    p_ = static_cast<uint16_t>(p + (up & ~mask) - (down & mask));
  }

 private:
  void Move(int bit, uint32_t rate) {
    const uint32_t p = p_;
    p_ = static_cast<uint16_t>(bit == 0 ? p + (((65536 - p) * rate) >> 16)
                                        : p - ((p * rate) >> 16));
  }

  uint16_t p_ = 32768;  // P(bit == 0) in units of 2^-16
  uint8_t count_ = 0;   // symbols seen, saturating at kAdaptCountLimit
};

}  // namespace meshwave

#endif  // MESHWAVE_ENTROPY_CONTEXT_MODEL_H_
