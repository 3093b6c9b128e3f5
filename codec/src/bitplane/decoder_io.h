// The decoder's symbol I/O policy of CodeBitplane (bitplane/bitplane_passes.h):
// reads the symbols back. The encoder's: bitplane/encoder_io.h.
#ifndef MESHWAVE_BITPLANE_DECODER_IO_H_
#define MESHWAVE_BITPLANE_DECODER_IO_H_

#include <cstdint>
#include <string_view>

#include "bitplane/coefficient_octree.h"
#include "entropy/arithmetic_decoder.h"

namespace meshwave {

// Holds the decoder by value, so that CodeBitplane's local copy keeps the
// coder's state in registers (through a reference, every store to the
// coefficient arrays could alias it and forced a reload per symbol).
class DecoderIo {
 public:
  explicit DecoderIo(std::string_view packet) : dec_(packet) {}
  int SigCoef(uint32_t, int, BinaryContext& ctx) { return dec_.Decode(ctx); }
  int SigNode(const OctreeNode&, int, BinaryContext& ctx) {
    return dec_.Decode(ctx);
  }
  // Signs and refinement bits are close to fair coins: decoded without a
  // branch on the symbol.
  int Sign(uint32_t, BinaryContext& ctx) { return dec_.DecodeUnpredictable(ctx); }
  int Refine(uint32_t, int, BinaryContext& ctx) { return dec_.DecodeUnpredictable(ctx); }
  const ArithmeticDecoder& decoder() const { return dec_; }

 private:
  ArithmeticDecoder dec_;
};

}  // namespace meshwave

#endif  // MESHWAVE_BITPLANE_DECODER_IO_H_
