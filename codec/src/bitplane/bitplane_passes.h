// The three passes of one bitplane of one (subband, component) — SIM's octree
// set partitioning with 3xC's optional parent contexts (Denis et al. 2010;
// 6.5). Written once as a template over the symbol I/O so that the encoder
// (which knows every coefficient) and the decoder (which learns them from
// the stream) run the very same steps and keep identical state.
#ifndef MESHWAVE_BITPLANE_BITPLANE_PASSES_H_
#define MESHWAVE_BITPLANE_BITPLANE_PASSES_H_

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "bitplane/coefficient_octree.h"
#include "entropy/context_model.h"

namespace meshwave {

// What the coder knows of one (subband, component) between bitplanes.
struct ComponentState {
  int top = -1;   // highest bitplane with a significant coefficient
  int next = -1;  // next bitplane to code; -1 when all are coded
  std::vector<std::vector<OctreeNode>> lin;  // insignificant cells per depth
  std::vector<uint32_t> lnc;  // coefficients coded alone, still insignificant
  std::vector<uint32_t> lsc;  // significant coefficients
  std::vector<uint32_t> mag;  // known bits of Q0 (lower bits zero)
  std::vector<uint8_t> negative;

  void Init(const CoefficientOctree& tree, int top_bitplane) {
    top = top_bitplane;
    next = top_bitplane;
    lin.clear();
    lnc.clear();
    lsc.clear();
    mag.assign(tree.size(), 0);
    negative.assign(tree.size(), 0);
    if (top < 0 || tree.size() == 0) return;
    const OctreeNode root = tree.Root();
    if (tree.IsLeaf(root)) {
      for (uint32_t i = root.begin; i < root.end; ++i) lnc.push_back(tree.At(i));
    } else {
      lin.resize(1);
      lin[0].push_back(root);
    }
  }
  // Lowest bitplane known so far (top + 1 before any).
  int known_from() const { return next + 1; }
};

// The adaptive contexts of one component in one packet; fresh per packet.
struct ComponentContexts {
  BinaryContext node[8];  // cell significance, by depth (capped)
  BinaryContext sig[6];   // 0-2 coded at a split, 3-5 in the NSP; + pstate
  BinaryContext sign[3];  // no parent info / parent positive / negative
  BinaryContext refine;
};

// The parent subband's magnitudes and signs as this coder may read them:
// the true values in the encoder, the decoded ones in the decoder; both give
// the same (Q0 >> b) for the bitplanes the dependency rules guarantee.
struct ParentView {
  std::span<const uint32_t> parent_of;  // coefficient -> parent; empty: none
  std::span<const uint32_t> mag;
  std::span<const uint8_t> negative;

  int State(uint32_t k, int b) const {
    if (parent_of.empty()) return 0;
    return static_cast<int>(std::min<uint32_t>(mag[parent_of[k]] >> b, 2));
  }
  int SignContext(uint32_t k, int state) const {
    if (state == 0) return 0;
    return negative[parent_of[k]] ? 2 : 1;
  }
};

// Io provides: int SigCoef(k, b, ctx), int SigNode(node, b, ctx),
// int Sign(k, ctx), int Refine(k, b, ctx). Each returns the symbol (the
// encoder codes the truth, the decoder decodes). `touched`, if not null,
// collects coefficients whose reconstruction changes.
template <class Io>
void CodeBitplane(const CoefficientOctree& tree, ComponentState& s, int b,
                  const ParentView& parent_view, ComponentContexts& ctx,
                  Io& io_state, std::vector<uint32_t>* touched) {
  // Local copies: a store to the coefficient arrays cannot alias them, so
  // the compiler need not reload the coder's state after each one (8 % fewer
  // instructions per decoded packet, measured with cachegrind).
  Io io = io_state;
  const ParentView parent = parent_view;
  // Coefficients significant in this bitplane are appended to s.lsc; the
  // refinement pass reads only the ones before them.
  const size_t refine_count = s.lsc.size();
  auto become_significant = [&](uint32_t k) {
    s.mag[k] |= 1u << b;
    const int state = parent.State(k, b);
    s.negative[k] = static_cast<uint8_t>(
        io.Sign(k, ctx.sign[parent.SignContext(k, state)]));
    s.lsc.push_back(k);
  };
  // 1. Non-significance pass: coefficients already seen one by one.
  size_t kept = 0;
  for (size_t i = 0; i < s.lnc.size(); ++i) {
    const uint32_t k = s.lnc[i];
    if (io.SigCoef(k, b, ctx.sig[3 + parent.State(k, b)])) {
      become_significant(k);
    } else {
      s.lnc[kept++] = k;
    }
  }
  s.lnc.resize(kept);
  // 2. Significance pass: cells by depth; a significant cell splits and its
  // children are visited in this same pass.
  // Cells that stay insignificant are compacted in place (children go to
  // depth d + 1, never to d).
  std::array<OctreeNode, 8> children;
  for (size_t d = 0; d < s.lin.size(); ++d) {
    size_t still = 0;
    for (size_t i = 0; i < s.lin[d].size(); ++i) {
      const OctreeNode node = s.lin[d][i];
      // The root is significant at the top bitplane by definition.
      const bool known = node.depth == 0 && b == s.top;
      if (!known && !io.SigNode(node, b, ctx.node[std::min<uint32_t>(d, 7)])) {
        s.lin[d][still++] = node;
        continue;
      }
      const int n = tree.Children(node, children);
      for (int c = 0; c < n; ++c) {
        const OctreeNode& child = children[c];
        if (!tree.IsLeaf(child)) {
          if (s.lin.size() <= d + 1) s.lin.resize(d + 2);
          s.lin[d + 1].push_back(child);
          continue;
        }
        for (uint32_t p = child.begin; p < child.end; ++p) {
          const uint32_t k = tree.At(p);
          if (io.SigCoef(k, b, ctx.sig[parent.State(k, b)])) {
            become_significant(k);
          } else {
            s.lnc.push_back(k);
          }
        }
      }
    }
    s.lin[d].resize(still);
  }
  // 3. Refinement pass: coefficients significant before this bitplane.
  for (size_t i = 0; i < refine_count; ++i) {
    const uint32_t k = s.lsc[i];
    s.mag[k] |= static_cast<uint32_t>(io.Refine(k, b, ctx.refine)) << b;
  }
  if (touched != nullptr) {
    touched->insert(touched->end(), s.lsc.begin(), s.lsc.end());
  }
  s.next = b - 1;
  io_state = io;
}

}  // namespace meshwave

#endif  // MESHWAVE_BITPLANE_BITPLANE_PASSES_H_
