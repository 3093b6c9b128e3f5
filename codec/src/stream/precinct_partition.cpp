#include "stream/precinct_partition.h"

#include <algorithm>
#include <utility>

#include "core/hilbert_order.h"
#include "semiregular/base_face_of.h"

namespace meshwave {
namespace {

// Cuts face_order[begin, end) into runs of >= `least` coefficients,
// appending each run's end to `bounds`.
void CutRuns(const std::vector<uint32_t>& face_order, const std::vector<uint32_t>& held,
             uint32_t begin, uint32_t end, uint64_t least, std::vector<uint32_t>& bounds) {
  const size_t first_cut = bounds.size();
  uint64_t run = 0;
  for (uint32_t i = begin; i < end; ++i) {
    run += held[face_order[i]];
    if (run >= least && i + 1 < end) {
      bounds.push_back(i + 1);
      run = 0;
    }
  }
  // The remainder (face_order[last cut, end)) joins the run before it when
  // under half a run.
  if (bounds.size() > first_cut && 2 * run < least) bounds.pop_back();
  bounds.push_back(end);
}

}  // namespace

std::vector<uint32_t> PrecinctPartition::FacePrecincts(int j) const {
  std::vector<uint32_t> out(face_order.size());
  const auto& b = bounds[static_cast<size_t>(j)];
  for (uint32_t p = 0; p + 1 < b.size(); ++p) {
    for (uint32_t i = b[p]; i < b[p + 1]; ++i) out[face_order[i]] = p;
  }
  return out;
}

uint32_t PrecinctPartition::Parent(int j, uint32_t p) const {
  const auto& above = bounds[static_cast<size_t>(j) - 1];
  const uint32_t first_face = bounds[static_cast<size_t>(j)][p];
  // The last run of j - 1 starting at or before the precinct's first face.
  return static_cast<uint32_t>(std::upper_bound(above.begin(), above.end(), first_face) -
                               above.begin() - 1);
}

std::vector<std::vector<uint32_t>> PrecinctPartition::FacePrecinctsPerSubband() const {
  std::vector<std::vector<uint32_t>> out;
  for (int j = 0; j < levels(); ++j) out.push_back(FacePrecincts(j));
  return out;
}

std::vector<std::vector<uint32_t>> PrecinctPartition::ParentsPerSubband() const {
  std::vector<std::vector<uint32_t>> out(bounds.size());
  for (int j = 1; j < levels(); ++j) {
    for (uint32_t p = 0; p < count(j); ++p) out[static_cast<size_t>(j)].push_back(Parent(j, p));
  }
  return out;
}

PrecinctPartition PartitionIntoPrecincts(const SemiRegularHierarchy& h,
                                         std::span<const IntVec3> base_grid,
                                         uint32_t min_coefficients) {
  PrecinctPartition out;
  const auto& faces = h.faces(0);
  if (min_coefficients == 0) {
    out.face_order.reserve(faces.size());
    for (uint32_t f = 0; f < faces.size(); ++f) out.face_order.push_back(f);
    const std::vector<uint32_t> whole = {0, static_cast<uint32_t>(faces.size())};
    for (int j = 0; j < h.levels(); ++j) out.bounds.push_back(whole);
    return out;
  }
  // 3 x each centroid: exact integers, the order the decoder derives too.
  std::vector<IntVec3> centroids(faces.size());
  for (size_t f = 0; f < faces.size(); ++f) {
    for (int a = 0; a < 3; ++a) {
      centroids[f][a] = base_grid[faces[f][0]][a] + base_grid[faces[f][1]][a] +
                        base_grid[faces[f][2]][a];
    }
  }
  out.face_order = HilbertOrder(centroids);
  const uint64_t least = min_coefficients;
  const uint32_t face_count = static_cast<uint32_t>(faces.size());
  std::vector<uint32_t> above = {0, face_count};
  for (int j = 0; j < h.levels(); ++j) {
    std::vector<uint32_t> held(faces.size(), 0);
    AddCoefficientsPerBaseFace(h, j, held);
    std::vector<uint32_t> bounds = {0};
    for (size_t p = 0; p + 1 < above.size(); ++p) {
      CutRuns(out.face_order, held, above[p], above[p + 1], least, bounds);
    }
    out.bounds.push_back(bounds);
    above = std::move(bounds);
  }
  return out;
}

std::vector<uint32_t> CoefficientPrecincts(const SemiRegularHierarchy& h,
                                           const PrecinctPartition& partition, int j) {
  const std::vector<uint32_t> of_face = partition.FacePrecincts(j);
  std::vector<uint32_t> out(h.subband_size(j));
  for (uint32_t k = 0; k < out.size(); ++k) out[k] = of_face[BaseFaceOf(h, j, k)];
  return out;
}

}  // namespace meshwave
