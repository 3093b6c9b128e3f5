#include "pgc/zerotree_coder.h"

namespace meshwave {

void ZerotreeState::Init(const SemiRegularHierarchy& h, std::span<const int> top) {
  const int levels = static_cast<int>(top.size());
  top_.assign(top.begin(), top.end());
  top_below_.assign(levels, -1);
  for (int j = levels - 1; j >= 0; --j) {
    top_below_[j] = std::max(top_[j], j + 1 < levels ? top_below_[j + 1] : -1);
  }
  next_ = this->top();
  lip_.clear();
  lis_.clear();
  lsp_.clear();
  mag_.resize(levels);
  negative_.resize(levels);
  for (int j = 0; j < levels; ++j) {
    mag_[j].assign(h.subband_size(j), 0);
    negative_[j].assign(h.subband_size(j), 0);
  }
  if (levels == 0) return;
  // Roots: every coefficient of d^0, and its descendants as one set when it
  // has any.
  const auto roots = static_cast<uint32_t>(h.subband_size(0));
  lip_.reserve(roots);
  for (uint32_t k = 0; k < roots; ++k) lip_.push_back(TreeNode{k, 0});
  if (levels > 1) {
    lis_.reserve(roots);
    for (uint32_t k = 0; k < roots; ++k) lis_.push_back(TreeSet{k, 0, 0, 0});
  }
}

ZerotreeSetMaxima ComputeZerotreeSetMaxima(
    const SemiRegularHierarchy& h, std::span<const std::vector<uint32_t>> q0) {
  const int levels = static_cast<int>(q0.size());
  ZerotreeSetMaxima out;
  out.d.resize(levels);
  out.l.resize(levels);
  std::array<uint32_t, 4> children;
  // Bottom-up: D(e) = children and their D sets; L(e) = the children's D sets.
  for (int j = levels - 2; j >= 0; --j) {
    const size_t size = h.subband_size(j);
    const bool child_has_d = j + 2 < levels;
    out.d[j].assign(size, 0);
    if (child_has_d) out.l[j].assign(size, 0);
    for (uint32_t k = 0; k < size; ++k) {
      const int count = h.Children(j, k, children);
      uint32_t d = 0, l = 0;
      for (int c = 0; c < count; ++c) {
        const uint32_t o = children[c];
        d = std::max(d, q0[j + 1][o]);
        if (child_has_d) l = std::max(l, out.d[j + 1][o]);
      }
      out.d[j][k] = std::max(d, l);
      if (child_has_d) out.l[j][k] = l;
    }
  }
  return out;
}

}  // namespace meshwave
