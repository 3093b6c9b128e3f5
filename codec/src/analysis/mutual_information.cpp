#include "analysis/mutual_information.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <numeric>
#include <random>

namespace meshwave {
namespace {

constexpr int kMaxDims = 3;

// 95 % quantiles of chi^2 with 2^d - 1 degrees of freedom: the uniformity
// test of a cell split into 2^d sub-cells (Darbellay & Vajda).
double ChiSquare95(int dims) { return dims == 2 ? 7.815 : dims == 3 ? 14.067 : 3.841; }

struct Cell {
  std::array<uint32_t, kMaxDims> lo{}, hi{};  // inclusive rank intervals
  size_t begin = 0, end = 0;                  // range of `order`
  bool root = false;
};

}  // namespace

double MultiInformation(const std::vector<std::span<const double>>& columns,
                        uint64_t seed) {
  const int d = static_cast<int>(columns.size());
  assert(d >= 2 && d <= kMaxDims);
  const size_t n = columns[0].size();
  for (const auto& column : columns) {
    if (column.size() != n) return 0.0;  // contract: equal lengths
  }
  if (n < 8) return 0.0;

  // Ranks make every marginal uniform; random tie-breaking keeps blocks of
  // equal values (exact zeros on flat regions) from forming false structure.
  std::mt19937_64 rng(seed);
  std::vector<uint32_t> ranks(n * static_cast<size_t>(d));
  std::vector<uint32_t> perm(n), idx(n);
  for (int k = 0; k < d; ++k) {
    std::iota(perm.begin(), perm.end(), 0u);
    std::shuffle(perm.begin(), perm.end(), rng);
    std::vector<uint32_t> tiebreak(n);
    for (size_t i = 0; i < n; ++i) tiebreak[perm[i]] = static_cast<uint32_t>(i);
    std::iota(idx.begin(), idx.end(), 0u);
    const auto& col = columns[static_cast<size_t>(k)];
    std::sort(idx.begin(), idx.end(), [&](uint32_t a, uint32_t b) {
      return col[a] < col[b] || (col[a] == col[b] && tiebreak[a] < tiebreak[b]);
    });
    for (size_t r = 0; r < n; ++r) ranks[idx[r] * static_cast<size_t>(d) + static_cast<size_t>(k)] = static_cast<uint32_t>(r);
  }

  std::vector<uint32_t> order(n), scratch(n);
  std::iota(order.begin(), order.end(), 0u);
  const int sub = 1 << d;
  const double threshold = ChiSquare95(d);
  double sum = 0;  // sum over final cells of N_c ln(N_c / prod n_k)
  const auto finalize = [&](const Cell& c) {
    const double count = static_cast<double>(c.end - c.begin);
    if (count <= 0) return;
    double log_volume = 0;
    for (int k = 0; k < d; ++k) log_volume += std::log(static_cast<double>(c.hi[k] - c.lo[k] + 1));
    sum += count * (std::log(count) - log_volume);
  };

  std::vector<Cell> stack;
  Cell root;
  root.end = n;
  root.root = true;
  for (int k = 0; k < d; ++k) root.hi[k] = static_cast<uint32_t>(n - 1);
  stack.push_back(root);
  while (!stack.empty()) {
    const Cell c = stack.back();
    stack.pop_back();
    bool splittable = true;
    std::array<uint32_t, kMaxDims> mid{};
    for (int k = 0; k < d; ++k) {
      if (c.hi[k] == c.lo[k]) splittable = false;
      mid[k] = c.lo[k] + (c.hi[k] - c.lo[k]) / 2;
    }
    if (!splittable) {
      finalize(c);
      continue;
    }
    // Counting sort of the cell's points by sub-cell.
    std::array<size_t, 1 << kMaxDims> counts{};
    const auto code = [&](uint32_t p) {
      int b = 0;
      for (int k = 0; k < d; ++k) {
        b |= (ranks[p * static_cast<size_t>(d) + static_cast<size_t>(k)] > mid[k]) << k;
      }
      return b;
    };
    for (size_t i = c.begin; i < c.end; ++i) ++counts[static_cast<size_t>(code(order[i]))];
    const double total = static_cast<double>(c.end - c.begin);
    const double expected = total / sub;
    double chi2 = 0;
    for (int b = 0; b < sub; ++b) {
      const double e = static_cast<double>(counts[static_cast<size_t>(b)]) - expected;
      chi2 += e * e;
    }
    chi2 /= expected;
    if (!c.root && chi2 < threshold) {
      finalize(c);
      continue;
    }
    std::array<size_t, (1 << kMaxDims) + 1> start{};
    start[0] = c.begin;
    for (int b = 0; b < sub; ++b) start[static_cast<size_t>(b) + 1] = start[static_cast<size_t>(b)] + counts[static_cast<size_t>(b)];
    std::array<size_t, 1 << kMaxDims> fill{};
    for (int b = 0; b < sub; ++b) fill[static_cast<size_t>(b)] = start[static_cast<size_t>(b)];
    for (size_t i = c.begin; i < c.end; ++i) {
      const uint32_t p = order[i];
      scratch[fill[static_cast<size_t>(code(p))]++] = p;
    }
    std::copy(scratch.begin() + static_cast<ptrdiff_t>(c.begin),
              scratch.begin() + static_cast<ptrdiff_t>(c.end),
              order.begin() + static_cast<ptrdiff_t>(c.begin));
    for (int b = 0; b < sub; ++b) {
      Cell s;
      for (int k = 0; k < d; ++k) {
        const bool upper = (b >> k) & 1;
        s.lo[k] = upper ? mid[k] + 1 : c.lo[k];
        s.hi[k] = upper ? c.hi[k] : mid[k];
      }
      s.begin = start[static_cast<size_t>(b)];
      s.end = start[static_cast<size_t>(b) + 1];
      // Cells of two points or fewer cannot be tested further.
      if (s.end - s.begin <= 2) {
        finalize(s);
      } else {
        stack.push_back(s);
      }
    }
  }
  const double nd = static_cast<double>(n);
  const double nats = sum / nd + (d - 1) * std::log(nd);
  return nats / std::log(2.0);
}

double MutualInformation(std::span<const double> x, std::span<const double> y) {
  return MultiInformation({x, y});
}

double MutualInformation(std::span<const double> x, std::span<const double> y,
                         std::span<const double> z) {
  return MultiInformation({x, y, z}) - MultiInformation({y, z});
}

}  // namespace meshwave
