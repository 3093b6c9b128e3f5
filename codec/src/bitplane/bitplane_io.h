// The two symbol I/O policies of CodeBitplane: EncoderIo codes the true
// symbols of known coefficients, DecoderIo reads them back.
#ifndef MESHWAVE_BITPLANE_BITPLANE_IO_H_
#define MESHWAVE_BITPLANE_BITPLANE_IO_H_

#include <cstdint>
#include <span>
#include <string_view>

#include "bitplane/coefficient_octree.h"
#include "entropy/arithmetic_decoder.h"
#include "entropy/arithmetic_encoder.h"

namespace meshwave {

// `q0` and `negative` in the subband's Morton order, as CodeBitplane names
// coefficients.
class EncoderIo {
 public:
  EncoderIo(ArithmeticEncoder& enc, std::span<const uint32_t> q0,
            std::span<const uint8_t> negative)
      : enc_(&enc), q0_(q0), negative_(negative) {}

  int SigCoef(uint32_t i, int b, BinaryContext& ctx) {
    return Put((q0_[i] >> b) & 1, ctx);
  }
  int SigNode(const OctreeNode& node, int b, BinaryContext& ctx) {
    const uint32_t threshold = 1u << b;
    int sig = 0;
    for (uint32_t i = node.begin; i < node.end && !sig; ++i) {
      sig = q0_[i] >= threshold;
    }
    return Put(sig, ctx);
  }
  int Sign(uint32_t i, BinaryContext& ctx) { return Put(negative_[i], ctx); }
  int Refine(uint32_t i, int b, BinaryContext& ctx) {
    return Put((q0_[i] >> b) & 1, ctx);
  }

 private:
  int Put(int bit, BinaryContext& ctx) {
    enc_->Encode(bit, ctx);
    return bit;
  }
  // A pointer, not a reference: CodeBitplane works on a copy and assigns it
  // back.
  ArithmeticEncoder* enc_;
  std::span<const uint32_t> q0_;
  std::span<const uint8_t> negative_;
};

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

#endif  // MESHWAVE_BITPLANE_BITPLANE_IO_H_
