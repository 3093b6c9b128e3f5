// The encoder's symbol I/O policy of CodeBitplane (bitplane/bitplane_passes.h):
// codes the true symbols of known coefficients. The decoder's:
// bitplane/decoder_io.h.
#ifndef MESHWAVE_BITPLANE_ENCODER_IO_H_
#define MESHWAVE_BITPLANE_ENCODER_IO_H_

#include <cstdint>
#include <span>

#include "bitplane/coefficient_octree.h"
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

}  // namespace meshwave

#endif  // MESHWAVE_BITPLANE_ENCODER_IO_H_
