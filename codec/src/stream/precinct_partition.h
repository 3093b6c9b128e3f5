// Precincts (issue 21): groups of base faces whose coefficients can travel
// in packets of their own, so that a stream can refine one region of the
// surface before the rest, as JPEG 2000's precincts do for images. Every
// coefficient descends from one base face (semiregular/base_face_of.h),
// so a group of base faces and their subtrees is a spatial unit.
//
// The partition is derived, not transmitted: base faces in the Hilbert order
// (core/hilbert_order.h) of their centroids on the integer grid of the
// header's base mesh, cut into runs that hold
// at least `min_coefficients` coefficients of the subband. Runs nest: each
// subband's precincts split the coarser subband's, so that a precinct's
// parent coefficients lie in one precinct of the subband above (those on
// its border excepted, which belong to a neighbour's base face).
#ifndef MESHWAVE_STREAM_PRECINCT_PARTITION_H_
#define MESHWAVE_STREAM_PRECINCT_PARTITION_H_

#include <cstdint>
#include <span>
#include <vector>

#include "bitplane/coefficient_octree.h"
#include "meshwave/semiregular.h"

namespace meshwave {

struct PrecinctPartition {
  // Base faces in the Hilbert order of their centroids.
  std::vector<uint32_t> face_order;
  // bounds[j]: precinct p of subband j holds the base faces
  // face_order[bounds[j][p], bounds[j][p + 1]).
  std::vector<std::vector<uint32_t>> bounds;

  int levels() const { return static_cast<int>(bounds.size()); }
  uint32_t count(int j) const {
    return static_cast<uint32_t>(bounds[static_cast<size_t>(j)].size() - 1);
  }
  // The precinct of every base face in subband j.
  std::vector<uint32_t> FacePrecincts(int j) const;
  // The precinct of subband j - 1 that precinct p of subband j lies in
  // (j >= 1; the runs nest).
  uint32_t Parent(int j, uint32_t p) const;
  // FacePrecincts and Parent of every subband, as SubbandLayoutBuilder
  // takes them (parents[0] is empty).
  std::vector<std::vector<uint32_t>> FacePrecinctsPerSubband() const;
  std::vector<std::vector<uint32_t>> ParentsPerSubband() const;
};

// Runs of at least `min_coefficients` coefficients of each subband (a
// subband, or a coarser precinct, holding fewer stays whole); a last run
// under half of that joins the one before it. 0: one precinct per subband
// (as streams before version 7, and streams encoded without precincts).
PrecinctPartition PartitionIntoPrecincts(const SemiRegularHierarchy& h,
                                         std::span<const IntVec3> base_grid,
                                         uint32_t min_coefficients);

// The precinct of every coefficient of subband j.
std::vector<uint32_t> CoefficientPrecincts(const SemiRegularHierarchy& h,
                                           const PrecinctPartition& partition, int j);

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_PRECINCT_PARTITION_H_
