#include "wavelet/sawt_choice.h"

#include <limits>
#include <string>

#include "semiregular/vertex_rings.h"
#include "wavelet/prediction_stencils.h"
#include "wavelet/sawt_index_model.h"

namespace meshwave {

Result<std::shared_ptr<const SawtPlan>> ChooseSawtFilters(
    const SemiRegularHierarchy& h, SawtRegions regions,
    std::span<const Vec3> positions, UpdateWeights update, double lambda) {
  const int levels = h.levels();
  if (positions.size() != h.vertex_count(levels)) {
    return InvalidArgument("SAWT: positions do not match the hierarchy");
  }
  auto plan = std::make_shared<SawtPlan>();
  plan->filters.assign(levels, std::vector<SawtFilter>(regions.count, SawtFilter::kButterfly));
  std::vector<Vec3> x(positions.begin(), positions.end());
  SawtSideModel model;
  for (int j = levels - 1; j >= 0; --j) {
    auto rings = VertexRings::Build(h.vertex_count(j), h.faces(j));
    if (!rings.ok()) return rings.status().WithContext("level " + std::to_string(j));
    const uint32_t vj = h.vertex_count(j);
    const uint32_t n = static_cast<uint32_t>(h.subband_size(j));
    const std::vector<uint32_t> region = SawtOddVertexRegions(h, j, regions.face_region);
    std::vector<StencilTable> tables;
    for (int l = 0; l < kSawtFilterCount; ++l) {
      const std::vector<SawtFilter> all(n, static_cast<SawtFilter>(l));
      tables.push_back(BuildSawtStencils(h, j, *rings, all));
    }
    // Squared prediction error of every filter, summed per region.
    std::vector<std::array<double, kSawtFilterCount>> error(regions.count);
    std::vector<uint32_t> count(regions.count, 0);
    for (auto& e : error) e.fill(0);
    for (uint32_t k = 0; k < n; ++k) {
      const Vec3& c = x[vj + k];
      for (int l = 0; l < kSawtFilterCount; ++l) {
        error[region[k]][l] += (c - PredictWithStencil(tables[l], k, x.data())).squaredNorm();
      }
      ++count[region[k]];
    }
    std::vector<SawtFilter>& chosen = plan->filters[j];
    for (uint32_t r = 0; r < regions.count; ++r) {
      if (count[r] == 0) continue;  // not coded (ForEachCodedSawtChoice)
      double best = std::numeric_limits<double>::infinity();
      for (int l = 0; l < kSawtFilterCount; ++l) {
        const SawtFilter f = static_cast<SawtFilter>(l);
        const double cost = error[r][l] / count[r] + lambda * model.IndexCost(f);
        if (cost < best) {
          best = cost;
          chosen[r] = f;
        }
      }
      model.Observe(chosen[r]);
    }
    // Forward step of this level with the chosen filters.
    Vec3* odd = x.data() + vj;
    for (uint32_t k = 0; k < n; ++k) {
      odd[k] -= PredictWithStencil(tables[static_cast<int>(chosen[region[k]])], k, x.data());
    }
    const auto weights = BuildUpdateWeights(h, j, *rings, update);
    if (!weights.empty()) {
      const auto& edges = h.edges(j);
      for (uint32_t k = 0; k < n; ++k) {
        x[edges[k][0]] += weights[k][0] * odd[k];
        x[edges[k][1]] += weights[k][1] * odd[k];
      }
    }
  }
  plan->regions = std::move(regions);
  return std::shared_ptr<const SawtPlan>(std::move(plan));
}

std::array<uint32_t, kSawtFilterCount> SawtFilterUsage(const SemiRegularHierarchy& h,
                                                       const SawtPlan& plan) {
  std::array<uint32_t, kSawtFilterCount> usage{};
  ForEachCodedSawtChoice(h, plan.regions, [&](int j, uint32_t r) {
    ++usage[static_cast<int>(plan.filters[j][r])];
  });
  return usage;
}

}  // namespace meshwave
