// PGC's zerotree bitplane coder (Khodakovsky et al. 2000): SPIHT-style set
// partitioning over the coefficient trees of the hierarchy (docs/CODEC.md,
// docs/CODEC.md), one tree per coefficient of d^0 and per component, each
// node with the 4 (3 on a boundary) children of SemiRegularHierarchy. A tree
// spans every level, so one bitplane touches all subbands: no resolution
// scalability, quality order only. The comparison baseline for SIM and 3xC.
//
// Like bitplane_passes.h, the passes are written once as a template over the
// symbol I/O, so that the encoder (which knows every coefficient) and the
// decoder (which learns them from the stream) run the very same steps.
#ifndef MESHWAVE_PGC_ZEROTREE_CODER_H_
#define MESHWAVE_PGC_ZEROTREE_CODER_H_

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "entropy/arithmetic_decoder.h"
#include "entropy/arithmetic_encoder.h"
#include "entropy/context_model.h"
#include "meshwave/semiregular.h"

namespace meshwave {

// Coefficient k of subband d^j.
struct TreeNode {
  uint32_t k = 0;
  uint32_t j = 0;
};

// An entry of the list of insignificant sets: the descendants D(e) of
// coefficient e (type A) or its grand-descendants L(e) = D(e) minus the
// children (type B).
struct TreeSet {
  uint32_t k = 0;
  uint16_t j = 0;
  uint8_t type_b = 0;
  // Type B only, within the pass that created it: D(e) was significant and
  // no child was, so L(e) is significant without a symbol.
  uint8_t known_significant = 0;
};

// The adaptive contexts of one component in one packet; fresh per packet.
// Significance contexts are split by subband level (capped): coarse
// coefficients and sets turn significant at other rates than fine ones.
struct ZerotreeContexts {
  static constexpr uint32_t kLevels = 8;
  static uint32_t Level(uint32_t j) { return std::min(j, kLevels - 1); }
  BinaryContext lip[kLevels];    // a coefficient of the LIP
  BinaryContext child[kLevels];  // a child of a significant D set
  BinaryContext set_d[kLevels];  // a D set, by the level of its root
  BinaryContext set_l[kLevels];  // an L set, by the level of its root
  BinaryContext sign;
  BinaryContext refine;
};

// What the coder knows of one component (all its trees) between bitplanes.
class ZerotreeState {
 public:
  // Every coefficient insignificant; `top[j]` = top bitplane of (d^j, this
  // component) from the header (-1: all zero). The header's top bitplanes
  // let both sides skip symbols whose value they already know.
  void Init(const SemiRegularHierarchy& h, std::span<const int> top);

  int levels() const { return static_cast<int>(top_.size()); }
  // Highest bitplane of any coefficient of the component (-1: none).
  int top() const { return top_.empty() ? -1 : top_below_[0]; }
  // Lowest bitplane known so far (top() + 1 before any was coded).
  int known_from() const { return next_ + 1; }

  // Known bits of Q0 (lower bits zero) and signs, per subband.
  const std::vector<uint32_t>& mag(int j) const { return mag_[j]; }
  const std::vector<uint8_t>& negative(int j) const { return negative_[j]; }
  // Significant coefficients, in the order they became so.
  const std::vector<TreeNode>& lsp() const { return lsp_; }

 private:
  template <class Io>
  friend void CodeZerotreeBitplane(const SemiRegularHierarchy& h,
                                   ZerotreeState& s, int b,
                                   ZerotreeContexts& ctx, Io& io);

  std::vector<int> top_;        // top bitplane of d^j
  std::vector<int> top_below_;  // top bitplane of d^j .. d^{J-1}
  int next_ = -1;               // next bitplane to code
  std::vector<TreeNode> lip_;   // insignificant coefficients
  std::vector<TreeSet> lis_;    // insignificant sets
  std::vector<TreeNode> lsp_;   // significant coefficients
  std::vector<std::vector<uint32_t>> mag_;
  std::vector<std::vector<uint8_t>> negative_;
};

// One bitplane b of one component: sorting pass (LIP, then LIS including the
// sets it appends), then refinement of the coefficients significant before b.
// Io provides int SigCoef(TreeNode, b, ctx), int SigSet(TreeSet, b, ctx),
// int Sign(TreeNode, ctx), int Refine(TreeNode, b, ctx), each returning the
// symbol (the encoder codes the truth, the decoder decodes). Bitplanes must
// come from s.top() down, one at a time.
template <class Io>
void CodeZerotreeBitplane(const SemiRegularHierarchy& h, ZerotreeState& s,
                          int b, ZerotreeContexts& ctx, Io& io) {
  const int levels = s.levels();
  // Above a subband's top bitplane every coefficient is known to be
  // insignificant, and so is every set of only such subbands.
  auto may_coef = [&](uint32_t j) { return b <= s.top_[j]; };
  auto may_below = [&](uint32_t j) {  // any of d^j .. d^{J-1}
    return static_cast<int>(j) < levels && b <= s.top_below_[j];
  };
  const size_t refine_count = s.lsp_.size();
  auto become_significant = [&](TreeNode n) {
    s.mag_[n.j][n.k] |= 1u << b;
    s.negative_[n.j][n.k] = static_cast<uint8_t>(io.Sign(n, ctx.sign));
    s.lsp_.push_back(n);
  };

  // 1. The insignificant coefficients.
  size_t kept = 0;
  for (size_t i = 0; i < s.lip_.size(); ++i) {
    const TreeNode n = s.lip_[i];
    if (may_coef(n.j) && io.SigCoef(n, b, ctx.lip[ZerotreeContexts::Level(n.j)])) {
      become_significant(n);
    } else {
      s.lip_[kept++] = n;
    }
  }
  s.lip_.resize(kept);

  // 2. The insignificant sets, including those appended during this pass;
  // the ones that stay insignificant keep their order.
  std::vector<TreeSet> still;
  std::array<uint32_t, 4> children;
  for (size_t i = 0; i < s.lis_.size(); ++i) {
    const TreeSet e = s.lis_[i];
    const uint32_t level = ZerotreeContexts::Level(e.j);
    if (!e.type_b) {
      if (!may_below(e.j + 1u) || !io.SigSet(e, b, ctx.set_d[level])) {
        still.push_back(e);
        continue;
      }
      // D(e) is significant: code the children one by one. When L(e) is
      // empty or known to be insignificant, a child must be significant, so
      // the last one is inferred if none before it was.
      const bool has_l = static_cast<int>(e.j) + 2 < levels;
      const bool l_may = has_l && may_below(e.j + 2u);
      const int count = h.Children(e.j, e.k, children);
      bool any = false;
      for (int c = 0; c < count; ++c) {
        const TreeNode child{children[c], e.j + 1u};
        int sig = 0;
        if (may_coef(child.j)) {
          sig = (c == count - 1 && !any && !l_may)
                    ? 1
                    : io.SigCoef(child, b, ctx.child[ZerotreeContexts::Level(child.j)]);
        }
        if (sig) {
          become_significant(child);
          any = true;
        } else {
          s.lip_.push_back(child);
        }
      }
      if (has_l) {
        s.lis_.push_back(TreeSet{e.k, e.j, 1, static_cast<uint8_t>(!any)});
      }
    } else {
      const bool sig = e.known_significant ||
                       (may_below(e.j + 2u) && io.SigSet(e, b, ctx.set_l[level]));
      if (!sig) {
        still.push_back(e);
        continue;
      }
      // L(e) is significant: each child becomes a D set of its own (each
      // has descendants, since e has grand-descendants).
      const int count = h.Children(e.j, e.k, children);
      for (int c = 0; c < count; ++c) {
        s.lis_.push_back(TreeSet{children[c], static_cast<uint16_t>(e.j + 1), 0, 0});
      }
    }
  }
  s.lis_.swap(still);

  // 3. Refinement of the coefficients significant before this bitplane.
  for (size_t i = 0; i < refine_count; ++i) {
    const TreeNode n = s.lsp_[i];
    s.mag_[n.j][n.k] |= static_cast<uint32_t>(io.Refine(n, b, ctx.refine)) << b;
  }
  s.next_ = b - 1;
}

// The largest Q0 in D(e) and in L(e) of every coefficient e of one component
// (encoder side; the decoder never has them).
struct ZerotreeSetMaxima {
  std::vector<std::vector<uint32_t>> d;  // per subband; empty for d^{J-1}
  std::vector<std::vector<uint32_t>> l;  // per subband; empty for d^{J-2..}
};
// q0[j][k]: the component's magnitudes in subband j.
ZerotreeSetMaxima ComputeZerotreeSetMaxima(
    const SemiRegularHierarchy& h, std::span<const std::vector<uint32_t>> q0);

// Codes the true symbols of one component.
class ZerotreeEncoderIo {
 public:
  ZerotreeEncoderIo(ArithmeticEncoder& enc,
                    std::span<const std::vector<uint32_t>> q0,
                    std::span<const std::vector<uint8_t>> negative,
                    const ZerotreeSetMaxima& maxima)
      : enc_(enc), q0_(q0), negative_(negative), maxima_(maxima) {}

  int SigCoef(TreeNode n, int b, BinaryContext& ctx) {
    return Put(q0_[n.j][n.k] >> b != 0, ctx);
  }
  int SigSet(const TreeSet& e, int b, BinaryContext& ctx) {
    const auto& max = e.type_b ? maxima_.l : maxima_.d;
    return Put(max[e.j][e.k] >> b != 0, ctx);
  }
  int Sign(TreeNode n, BinaryContext& ctx) { return Put(negative_[n.j][n.k], ctx); }
  int Refine(TreeNode n, int b, BinaryContext& ctx) {
    return Put((q0_[n.j][n.k] >> b) & 1, ctx);
  }

 private:
  int Put(int bit, BinaryContext& ctx) {
    enc_.Encode(bit, ctx);
    return bit;
  }
  ArithmeticEncoder& enc_;
  std::span<const std::vector<uint32_t>> q0_;
  std::span<const std::vector<uint8_t>> negative_;
  const ZerotreeSetMaxima& maxima_;
};

// Reads the symbols back.
class ZerotreeDecoderIo {
 public:
  explicit ZerotreeDecoderIo(ArithmeticDecoder& dec) : dec_(dec) {}
  int SigCoef(TreeNode, int, BinaryContext& ctx) { return dec_.Decode(ctx); }
  int SigSet(const TreeSet&, int, BinaryContext& ctx) { return dec_.Decode(ctx); }
  int Sign(TreeNode, BinaryContext& ctx) { return dec_.Decode(ctx); }
  int Refine(TreeNode, int, BinaryContext& ctx) { return dec_.Decode(ctx); }

 private:
  ArithmeticDecoder& dec_;
};

}  // namespace meshwave

#endif  // MESHWAVE_PGC_ZEROTREE_CODER_H_
