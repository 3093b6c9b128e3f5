// Subdivide: refine a coarse manifold mesh into a semi-regular one.
#include <cmath>
#include <numbers>

#include "meshwave/semiregular.h"
#include "meshwave/subdivision.h"
#include "meshwave/wavelet.h"
#include "semiregular/vertex_rings.h"

namespace meshwave {
namespace {

// Loop's vertex rule: moves the even vertices of level j (first V_j
// entries) from their old positions `old`.
void SmoothEvenVerticesLoop(const VertexRings& rings, std::span<const Vec3> old,
                            std::span<Vec3> out) {
  for (uint32_t v = 0; v < rings.vertex_count(); ++v) {
    auto ring = rings.Ring(v);
    if (rings.IsBoundary(v)) {
      out[v] = 0.75 * old[v] + 0.125 * (old[ring.front()] + old[ring.back()]);
      continue;
    }
    const double k = static_cast<double>(ring.size());
    const double c = 0.375 + 0.25 * std::cos(2 * std::numbers::pi / k);
    const double beta = (0.625 - c * c) / k;
    Vec3 sum = Vec3::Zero();
    for (uint32_t u : ring) sum += old[u];
    out[v] = (1 - k * beta) * old[v] + beta * sum;
  }
}

}  // namespace

Result<SubdivisionScheme> ParseSubdivisionScheme(const std::string& name) {
  if (name == "midpoint" || name == "linear") return SubdivisionScheme::kMidpoint;
  if (name == "loop") return SubdivisionScheme::kLoop;
  if (name == "butterfly") return SubdivisionScheme::kButterfly;
  return InvalidArgument("unknown subdivision scheme \"" + name +
                         "\" (expected midpoint, loop or butterfly)");
}

const char* SubdivisionSchemeName(SubdivisionScheme scheme) {
  switch (scheme) {
    case SubdivisionScheme::kMidpoint: return "midpoint";
    case SubdivisionScheme::kLoop: return "loop";
    case SubdivisionScheme::kButterfly: return "butterfly";
  }
  return "?";
}

Result<SemiRegularMesh> Subdivide(const TriMesh& base, int levels,
                                  SubdivisionScheme scheme) {
  if (base.positions.size() >= 0xffffffffu) {
    return InvalidArgument("base mesh has too many vertices");
  }
  MW_ASSIGN_OR_RETURN(
      auto hierarchy,
      SemiRegularHierarchy::Build(static_cast<uint32_t>(base.positions.size()),
                                  base.faces, levels));
  TransformSettings settings;
  settings.predictor = scheme == SubdivisionScheme::kButterfly
                           ? Predictor::kButterfly
                           : (scheme == SubdivisionScheme::kLoop
                                  ? Predictor::kLoop
                                  : Predictor::kLinear);
  settings.update = UpdateWeights::kNone;
  MW_ASSIGN_OR_RETURN(WaveletTransform transform,
                      WaveletTransform::Create(hierarchy, settings));
  SemiRegularMesh out;
  out.hierarchy = hierarchy;
  out.positions = base.positions;
  out.positions.resize(hierarchy->vertex_count(levels));
  std::vector<Vec3> old;
  for (int j = 0; j < levels; ++j) {
    const uint32_t vj = hierarchy->vertex_count(j);
    if (scheme == SubdivisionScheme::kLoop) {
      old.assign(out.positions.begin(), out.positions.begin() + vj);
    }
    transform.PredictLevel(j, out.positions);
    if (scheme == SubdivisionScheme::kLoop) {
      MW_ASSIGN_OR_RETURN(VertexRings rings,
                          VertexRings::Build(vj, hierarchy->faces(j)));
      SmoothEvenVerticesLoop(rings, old, out.positions);
    }
  }
  return out;
}

}  // namespace meshwave
