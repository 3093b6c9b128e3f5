// The adaptive binary models of the SAWT side information (docs/FORMAT.md
// "SAWT filter choices"): one context per octree depth for the split
// flags, and a truncated unary code of the filter index (0..5) with one
// context per unary position. The encoder's Lagrangian choice reads the
// same models for the rate of each index (-log2 p).
#ifndef MESHWAVE_WAVELET_SAWT_INDEX_MODEL_H_
#define MESHWAVE_WAVELET_SAWT_INDEX_MODEL_H_

#include <array>
#include <cmath>

#include "entropy/context_model.h"
#include "wavelet/sawt_plan.h"
#include "wavelet/sawt_regions.h"

namespace meshwave {

class SawtSideModel {
 public:
  // Bits the index would cost now.
  double IndexCost(SawtFilter filter) const {
    const int index = static_cast<int>(filter);
    double bits = 0;
    for (int i = 0; i < kSawtFilterCount - 1; ++i) {
      const double p0 = unary_[i].probability() / double(1 << kProbBits);
      const int bit = i < index ? 1 : 0;
      bits -= std::log2(bit == 0 ? p0 : 1 - p0);
      if (bit == 0) break;
    }
    return bits;
  }
  // Unary bits of `filter`: 1 while i < index, then a 0 unless index is 5.
  template <typename Visit>  // visit(bit, context)
  void ForEachIndexBit(SawtFilter filter, Visit&& visit) {
    const int index = static_cast<int>(filter);
    for (int i = 0; i < kSawtFilterCount - 1; ++i) {
      const int bit = i < index ? 1 : 0;
      visit(bit, unary_[i]);
      if (bit == 0) break;
    }
  }
  // Adapts the contexts as coding `filter` would.
  void Observe(SawtFilter filter) {
    ForEachIndexBit(filter, [](int bit, BinaryContext& ctx) { ctx.Update(bit); });
  }
  template <typename Decoder>
  SawtFilter DecodeIndex(Decoder& decoder) {
    int index = 0;
    while (index < kSawtFilterCount - 1 && decoder.Decode(unary_[index]) == 1) ++index;
    return static_cast<SawtFilter>(index);
  }
  BinaryContext& SplitContext(int depth) { return split_[depth]; }

 private:
  std::array<BinaryContext, kSawtFilterCount - 1> unary_;
  std::array<BinaryContext, kSawtMaxDepth + 1> split_;
};

}  // namespace meshwave

#endif  // MESHWAVE_WAVELET_SAWT_INDEX_MODEL_H_
