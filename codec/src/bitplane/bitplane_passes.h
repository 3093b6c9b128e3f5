// The three passes of one bitplane of one (subband, component) — SIM's octree
// set partitioning with 3xC's parent (Denis et al. 2010) and neighbour contexts.
// Written once as a template over the symbol I/O so that the encoder
// (which knows every coefficient) and the decoder (which learns them from
// the stream) run the very same steps and keep identical state.
#ifndef MESHWAVE_BITPLANE_BITPLANE_PASSES_H_
#define MESHWAVE_BITPLANE_BITPLANE_PASSES_H_

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "bitplane/coefficient_octree.h"
#include "entropy/context_model.h"

namespace meshwave {

// What the coder knows of one (subband, component) between bitplanes. Every
// coefficient is named by its Morton position in the subband's octree
// (bitplane/subband_layout.h says why); tree.At(i) is its coefficient.
struct ComponentState {
  int top = -1;   // highest bitplane with a significant coefficient
  int next = -1;  // next bitplane to code; -1 when all are coded
  std::vector<std::vector<OctreeNode>> lin;  // insignificant cells per depth
  // The two position lists, each in a buffer of the subband's size (a
  // position is in at most one of them), so that appending needs no
  // capacity check: LNC, coded alone and still insignificant, is
  // lnc[0, lnc_size); LSC, significant, is lsc[0, lsc_size).
  std::vector<uint32_t> lnc;
  std::vector<uint32_t> lsc;
  uint32_t lnc_size = 0;
  uint32_t lsc_size = 0;
  std::vector<uint32_t> mag;  // known bits of Q0 (lower bits zero)
  std::vector<uint8_t> negative;
  // Per position, how many of its neighbours are significant (3xC's nctx
  // before the cap; kept up to date only with neighbour contexts).
  std::vector<uint8_t> significant_neighbours;

  void Init(const CoefficientOctree& tree, int top_bitplane) {
    top = top_bitplane;
    next = top_bitplane;
    lin.clear();
    lnc_size = 0;
    lsc_size = 0;
    // One more than the positions: the zero an out-of-precinct parent
    // position reads (SubbandLayout::parent_position).
    mag.assign(tree.size() + 1, 0);
    negative.assign(tree.size() + 1, 0);
    significant_neighbours.assign(tree.size(), 0);
    if (top < 0 || tree.size() == 0) {
      lnc.clear();
      lsc.clear();
      return;
    }
    lnc.resize(tree.size());
    lsc.resize(tree.size());
    const OctreeNode root = tree.Root();
    if (tree.IsLeaf(root)) {
      for (uint32_t i = root.begin; i < root.end; ++i) lnc[lnc_size++] = i;
    } else {
      lin.resize(1);
      lin[0].push_back(root);
    }
  }
  // Lowest bitplane known so far (top + 1 before any).
  int known_from() const { return next + 1; }
  // Positions of the significant coefficients, in the order they became so.
  std::span<const uint32_t> significant() const { return {lsc.data(), lsc_size}; }
};

// The adaptive contexts of one packet (its components share them); fresh
// per packet: carrying them from one bitplane's packet to the next one's
// saved nothing measurable (0.0-0.05 % on elephant_subdiv2 and feline).
struct ComponentContexts {
  BinaryContext node[8];  // cell significance, by depth (capped)
  // Significance: [pass][parent state][significant neighbours, capped at
  // 2]; pass 0 codes at a split, pass 1 in the NSP. The neighbour classes 1
  // and 2 start from P(1) = 1/5 and 1/3 as if 2 symbols were seen (about
  // what the shared meshes give, 0.1-0.45 against 0.01-0.13 with no
  // significant neighbour): from 1/2, learning 12 more contexts per packet
  // cost a small mesh's first packets more than the neighbours saved.
  static constexpr BinaryContext kNoNeighbourStart{};
  static constexpr BinaryContext kOneNeighbourStart{52429, 2};
  static constexpr BinaryContext kTwoNeighboursStart{43691, 2};
  static constexpr std::array<BinaryContext, 3> kSigStart = {
      kNoNeighbourStart, kOneNeighbourStart, kTwoNeighboursStart};
  using SigRow = std::array<BinaryContext, 3>;  // by neighbour class
  std::array<std::array<SigRow, 3>, 2> sig = {
      {{kSigStart, kSigStart, kSigStart}, {kSigStart, kSigStart, kSigStart}}};
  BinaryContext sign[3];  // no parent info / parent positive / negative
  BinaryContext refine;
};

// What 3xC's contexts read besides the coded component itself (SIM: none).
// The parent subband's magnitudes and signs as this coder may read them:
// the true values in the encoder, the decoded ones in the decoder; both give
// the same (Q0 >> b) for the bitplanes the dependency rules guarantee. All
// three arrays are in Morton order (of this subband, then of the parent's).
// And the subband's own neighbours, whose state both sides share anyway.
struct ContextSources {
  std::span<const uint32_t> parent_position;  // empty: no parent contexts
  std::span<const uint32_t> mag;
  std::span<const uint8_t> negative;

  // kHas: whether parent_position is non-empty, a template argument so
  // that the coder's loops are compiled once with and once without the
  // lookups rather than testing it per symbol.
  template <bool kHas>
  int State(uint32_t i, int b) const {
    if constexpr (!kHas) {
      return 0;
    } else {
      return static_cast<int>(std::min<uint32_t>(mag[parent_position[i]] >> b, 2));
    }
  }
  template <bool kHas>
  int SignContext(uint32_t i, int state) const {
    if (!kHas || state == 0) return 0;
    return negative[parent_position[i]] ? 2 : 1;
  }
  // Same-subband neighbours (SubbandLayout::neighbour_position); empty: no
  // neighbour contexts.
  std::span<const uint32_t> neighbour_position;
};

// Io provides: int SigCoef(i, b, ctx), int SigNode(node, b, ctx),
// int Sign(i, ctx), int Refine(i, b, ctx), i a Morton position. Each returns
// the symbol (the encoder codes the truth, the decoder decodes). After the
// call, s.significant() holds every position whose reconstruction changed.
namespace bitplane_internal {

// The lists and arrays one pass works on, as plain pointers and counts.
// Each pass takes the coder by value and returns it: working on a local copy
// keeps the coder's state in registers, where through a reference every
// byte store to the arrays (signs, context counts) could alias it and forced
// a reload per symbol.
struct PassState {
  uint32_t* mag;
  uint8_t* negative;
  uint8_t* significant_neighbours;
  uint32_t* lnc;
  uint32_t* lsc;
  uint32_t lnc_size;
  uint32_t lsc_size;
};

// 3xC's nctx of position i: its significant neighbours, capped at 2. The
// counters go up as neighbours become significant (BecomeSignificant): a
// coefficient known to be significant has a known bit at or above the
// bitplane being coded, so a counter is the number of n with M(n) >> b != 0
// (FORMAT.md 5.3), read with one load per symbol instead of four.
template <bool kNeighbours>
inline int NeighbourClass(const PassState& p, uint32_t i) {
  if constexpr (!kNeighbours) {
    return 0;
  } else {
    return std::min<int>(p.significant_neighbours[i], 2);
  }
}

// Position i became significant at bitplane b: its sign, then the LSC.
template <bool kParents, bool kNeighbours, class Io>
inline void BecomeSignificant(uint32_t i, int b, int state, const ContextSources& sources,
                              ComponentContexts& ctx, PassState& p, Io& io) {
  p.mag[i] |= 1u << b;
  if constexpr (kNeighbours) {
    // A missing neighbour's slot names i itself: i's own counter is never
    // read again (it is significant now).
    const uint32_t* nb = &sources.neighbour_position[size_t{4} * i];
    for (int n = 0; n < 4; ++n) ++p.significant_neighbours[nb[n]];
  }
  const int sign_context = sources.SignContext<kParents>(i, state);
  p.negative[i] = static_cast<uint8_t>(io.Sign(i, ctx.sign[sign_context]));
  p.lsc[p.lsc_size++] = i;
}

// 1. Non-significance pass: coefficients already seen one by one.
template <bool kParents, bool kNeighbours, class Io>
Io NonSignificancePass(int b, const ContextSources sources, ComponentContexts& ctx, PassState& p,
                       Io io) {
  PassState local = p;
  uint32_t kept = 0;
  for (uint32_t n = 0; n < local.lnc_size; ++n) {
    const uint32_t i = local.lnc[n];
    const int state = sources.State<kParents>(i, b);
    const int near = NeighbourClass<kNeighbours>(local, i);
    if (io.SigCoef(i, b, ctx.sig[1][state][near])) {
      BecomeSignificant<kParents, kNeighbours>(i, b, state, sources, ctx, local, io);
    } else {
      local.lnc[kept++] = i;
    }
  }
  local.lnc_size = kept;
  p = local;
  return io;
}

// 2. Significance pass: cells by depth; a significant cell splits and its
// children are visited in this same pass. Cells that stay insignificant are
// compacted in place (children go to depth d + 1, never to d).
template <bool kParents, bool kNeighbours, class Io>
Io SignificancePass(const CoefficientOctree& tree, int b, int top, const ContextSources sources,
                    ComponentContexts& ctx, std::vector<std::vector<OctreeNode>>& lin,
                    PassState& p, Io io) {
  PassState local = p;
  std::array<OctreeNode, 8> children;
  for (size_t d = 0; d < lin.size(); ++d) {
    size_t still = 0;
    for (size_t n = 0; n < lin[d].size(); ++n) {
      const OctreeNode node = lin[d][n];
      // The root is significant at the top bitplane by definition.
      const bool known = node.depth == 0 && b == top;
      if (!known && !io.SigNode(node, b, ctx.node[std::min<uint32_t>(d, 7)])) {
        lin[d][still++] = node;
        continue;
      }
      const int count = tree.Children(node, children);
      for (int c = 0; c < count; ++c) {
        const OctreeNode& child = children[c];
        if (!tree.IsLeaf(child)) {
          if (lin.size() <= d + 1) lin.resize(d + 2);
          lin[d + 1].push_back(child);
          continue;
        }
        for (uint32_t i = child.begin; i < child.end; ++i) {
          const int state = sources.State<kParents>(i, b);
          const int near = NeighbourClass<kNeighbours>(local, i);
          if (io.SigCoef(i, b, ctx.sig[0][state][near])) {
            BecomeSignificant<kParents, kNeighbours>(i, b, state, sources, ctx, local, io);
          } else {
            local.lnc[local.lnc_size++] = i;
          }
        }
      }
    }
    lin[d].resize(still);
  }
  p = local;
  return io;
}

// 3. Refinement pass: the first `count` of the LSC, significant before b.
template <class Io>
Io RefinementPass(int b, uint32_t count, BinaryContext& ctx, const PassState& p, Io io) {
  uint32_t* const mag = p.mag;
  const uint32_t* const lsc = p.lsc;
  for (uint32_t n = 0; n < count; ++n) {
    const uint32_t i = lsc[n];
    mag[i] |= static_cast<uint32_t>(io.Refine(i, b, ctx)) << b;
  }
  return io;
}

template <bool kParents, bool kNeighbours, class Io>
void CodeBitplane(const CoefficientOctree& tree, ComponentState& s, int b,
                  const ContextSources& sources, ComponentContexts& ctx, Io& io) {
  PassState p{s.mag.data(), s.negative.data(), s.significant_neighbours.data(),
              s.lnc.data(), s.lsc.data(), s.lnc_size, s.lsc_size};
  // Coefficients significant in this bitplane are appended to the LSC; the
  // refinement pass reads only the ones before them.
  const uint32_t refine_count = p.lsc_size;
  io = NonSignificancePass<kParents, kNeighbours>(b, sources, ctx, p, io);
  io = SignificancePass<kParents, kNeighbours>(tree, b, s.top, sources, ctx, s.lin, p, io);
  io = RefinementPass(b, refine_count, ctx.refine, p, io);
  s.lnc_size = p.lnc_size;
  s.lsc_size = p.lsc_size;
  s.next = b - 1;
}

}  // namespace bitplane_internal

template <class Io>
void CodeBitplane(const CoefficientOctree& tree, ComponentState& s, int b,
                  const ContextSources& sources, ComponentContexts& ctx, Io& io) {
  if (sources.neighbour_position.empty()) {
    bitplane_internal::CodeBitplane<false, false>(tree, s, b, sources, ctx, io);
  } else if (sources.parent_position.empty()) {
    bitplane_internal::CodeBitplane<false, true>(tree, s, b, sources, ctx, io);
  } else {
    bitplane_internal::CodeBitplane<true, true>(tree, s, b, sources, ctx, io);
  }
}

}  // namespace meshwave

#endif  // MESHWAVE_BITPLANE_BITPLANE_PASSES_H_
