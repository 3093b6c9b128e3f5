// Surface fitting, fold repair stage: after projection and relaxation some
// faces of a level may be folded (turned against the input) or degenerate;
// their vertices move, on the surface, until they are not. The repair step
// of the fit-relax-repair loop of MPEG's Video-based Dynamic Mesh Coding
// (V-DMC, ISO/IEC 23090-29) remeshing, on the normal-mesh hierarchy of
// Guskov, Vidimče, Sweldens, Schröder, "Normal Meshes", SIGGRAPH 2000.
#ifndef MESHWAVE_REMESH_FOLD_REPAIR_H_
#define MESHWAVE_REMESH_FOLD_REPAIR_H_

#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "remesh/fit_state.h"
#include "semiregular/vertex_rings.h"

namespace meshwave::remesh {

// A face of a level is bad when it is degenerate (Compactness below
// kDegenerateCompactness) or folded (IsFlipped: its normal opposes the
// input's under it, the test MeasureQuality applies to the result).
// Every move is counted in stats.repair_moves; vertices move only onto
// better positions, so a level without bad faces is left as it is.
class FoldRepair {
 public:
  explicit FoldRepair(const FitState& state)
      : h_(state.hierarchy),
        surface_(state.surface),
        options_(state.options),
        positions_(state.positions),
        anchors_(state.anchors),
        stats_(state.stats) {}

  // Both steps on `level` (rings: its vertex rings): UntangleLevel then
  // FixFolds. Returns the number of bad faces left.
  size_t Run(int level, const VertexRings& rings);

  // options.repair_rounds parallel (Jacobi) rounds: the inner vertices of
  // bad faces (in the first half of the rounds only the new ones of this
  // level; in the last quarter also their neighbours and pinned vertices)
  // try the ring centroid and a ring kernel point (RingKernelPoint) in the
  // tangent plane of their good faces, projected onto the surface, and
  // keep whichever leaves their faces least folded and least thin. The
  // moves are judged by the remesh's own normals. Returns the number of bad
  // faces left.
  size_t UntangleLevel(int level, const VertexRings& rings);

  // The faces still bad, judged exactly, one at a time in index order
  // (sequential, so every move is judged against the ring it will have):
  // a corner moves (toward its ring's centroid or kernel, or toward one
  // ring neighbour; on the surface or, failing that, just off it) when
  // fewer of its faces are then bad; failing that its neighbours may move
  // first; a corner on an input boundary loop slides along the loop.
  // A few sweeps. Returns the number of bad faces left.
  size_t FixFolds(int level, const VertexRings& rings);

 private:
  size_t MarkBadFaces(int level, bool new_only);
  void GrowMarks(const VertexRings& rings);
  void Untangle(int level, const VertexRings& rings, bool move_pinned);
  std::vector<Vec3> ConsensusNormals(int level) const;
  std::pair<int, double> LocalBadness(const Vec3& p, const Vec3& facing,
                                      std::span<const uint32_t> ring) const;
  int FaceBadness(const Face& f) const;
  std::pair<int, double> RingBadness(uint32_t v, std::span<const uint32_t> ring,
                                     bool closed = true) const;
  bool TryFix(uint32_t v, const VertexRings& rings, bool allow_equal = false);
  bool SlideOnLoop(uint32_t v, const VertexRings& rings);

  const SemiRegularHierarchy& h_;
  const InputSurface& surface_;
  const FitOptions& options_;
  std::vector<Vec3>& positions_;
  std::vector<SurfaceAnchor>& anchors_;
  FitStats& stats_;
  std::vector<uint8_t> marked_;    // vertices allowed to move this round
  std::vector<uint8_t> bad_face_;  // of the level last checked
};

}  // namespace meshwave::remesh

#endif  // MESHWAVE_REMESH_FOLD_REPAIR_H_
