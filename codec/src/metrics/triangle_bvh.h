// TriangleBvh: a bounding-volume hierarchy over the triangles of a mesh for
// closest-point queries, the engine of the sampled surface distance.
#ifndef MESHWAVE_METRICS_TRIANGLE_BVH_H_
#define MESHWAVE_METRICS_TRIANGLE_BVH_H_

#include <algorithm>
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

#include "meshwave/mesh.h"

namespace meshwave::metrics {

// An axis-aligned box tree over triangles, split by a binned surface-area
// heuristic along the axis where the centroids spread most (median splits
// where that fails and deep down, so the depth stays bounded). Boxes are
// stored in float, rounded outward, to halve node size; triangles are kept
// in double, with their unit normals, copied into leaf order for locality.
// Immutable after construction and safe to query from several threads.
class TriangleBvh {
 public:
  static constexpr uint32_t kNoFace = std::numeric_limits<uint32_t>::max();
  // Bound on depth(): area-heuristic splits down to depth 32, then median
  // splits, at most 30 more levels for fewer than 2^32 faces and 4 faces a
  // leaf. A depth-first traversal that keeps one pending sibling per level
  // needs a stack of kMaxDepth + 1 entries.
  static constexpr int kMaxDepth = 62;
  static constexpr int kMaxStack = kMaxDepth + 1;

  struct Hit {
    double distance_squared = std::numeric_limits<double>::infinity();
    uint32_t face = kNoFace;  // index into the faces given to the builder
    Vec3 point = Vec3::Zero();  // closest point on that face
  };

  // Contract (asserted, not checked): every index of `faces` is below
  // positions.size(), and there are fewer than 2^32 - 1 faces. Callers that
  // hold untrusted meshes validate them first. Zero-area faces are fine.
  // `threads` (as ResolveThreads takes it) build the subtrees below the
  // first splits side by side; the tree is the same for any number.
  TriangleBvh(const std::vector<Vec3>& positions,
              const std::vector<Face>& faces, int threads = 1);

  // The closest point of all triangles to `p`. With no triangles the hit
  // has an infinite distance and face kNoFace. Among equally near faces any
  // one may be returned.
  Hit ClosestPoint(const Vec3& p) const { return ClosestPoint(p, kNoFace); }
  // Same, but first measures `hint_face` (for example the face found for the
  // previous, nearby query) so that most of the tree is pruned at once.
  // kNoFace or an out-of-range hint means no hint.
  Hit ClosestPoint(const Vec3& p, uint32_t hint_face) const;

  // Filtered queries (triangle_bvh_filtered.cpp), for the remesher: it
  // restricts a search to one connected component and to faces facing the
  // way it expects. `accept` gets an index into the builder's faces; it is
  // called only for faces whose box is still in reach.
  using FaceFilter = std::function<bool(uint32_t face)>;

  // ClosestPoint over the accepted faces only (the hint too) that are
  // nearer than sqrt(max_distance_squared). None: infinite distance and
  // kNoFace. A finite bound also prunes the search.
  Hit ClosestPointIf(const Vec3& p, uint32_t hint_face,
                     const FaceFilter& accept,
                     double max_distance_squared =
                         std::numeric_limits<double>::infinity()) const;

  struct LineHit {
    double t = std::numeric_limits<double>::infinity();  // signed
    uint32_t face = kNoFace;
    Vec3 point = Vec3::Zero();  // origin + t * direction
  };
  // Of the crossings of the line origin + t·direction, |t| <= max_abs_t,
  // with accepted triangles, the one nearest to the origin (smallest |t|;
  // either side). `direction` need not be unit length; t is in its units.
  // Triangles parallel to the line, degenerate ones and misses give
  // kNoFace. A crossing within about 1e-9 (barycentric) of an edge counts,
  // so a line through a shared edge is not lost between its two faces.
  LineHit NearestLineHit(const Vec3& origin, const Vec3& direction,
                         double max_abs_t, const FaceFilter& accept) const;

  size_t face_count() const { return triangles_.size(); }
  size_t node_count() const { return nodes_.size(); }
  // Levels below the root of the deepest leaf.
  int depth() const { return depth_; }

 private:
  // Internal node: count == 0, left child at index + 1, right child at
  // `start`. Leaf: triangles_[start, start + count).
  struct Node {
    float lo[3];
    float hi[3];
    uint32_t start;
    uint32_t count;
  };
  struct Triangle {
    Vec3 a, b, c;
    // Unit normal, zero for degenerate triangles: the distance to the plane
    // bounds the distance to the triangle from below, a cheap rejection.
    Vec3 normal;
    uint32_t face;
  };
  struct BuildItem;

  // Appends the node for items[begin, end) and its subtree to `nodes`
  // (child indices relative to nodes[0]); returns its index and raises
  // `max_depth` to its deepest leaf. With threads > 1 large subtrees are
  // built beside each other into separate vectors and appended in the
  // order a single thread makes them.
  static uint32_t Build(std::vector<BuildItem>& items, uint32_t begin,
                        uint32_t end, int depth, int threads,
                        std::vector<Node>& nodes, int& max_depth);
  // Reorders items[begin, end) into two non-empty halves; returns where the
  // second starts.
  static uint32_t Split(std::vector<BuildItem>& items, uint32_t begin,
                        uint32_t end, bool try_sah);
  void TestLeaf(const Node& node, const Vec3& p, Hit& best) const;
  void TestLeafIf(const Node& node, const Vec3& p, const FaceFilter& accept,
                  Hit& best) const;

  std::vector<Node> nodes_;
  std::vector<Triangle> triangles_;    // in leaf order
  std::vector<uint32_t> slot_of_face_;  // face index -> triangles_ index
  int depth_ = 0;
};

// Squared distance from p to the box [lo, hi] (0 inside): the traversals'
// lower bound for a node's faces.
inline double BoxDistanceSquared(const float lo[3], const float hi[3], const Vec3& p) {
  double sum = 0;
  for (int k = 0; k < 3; ++k) {
    const double below = static_cast<double>(lo[k]) - p[k];
    const double above = p[k] - static_cast<double>(hi[k]);
    const double gap = std::max({below, above, 0.0});
    sum += gap * gap;
  }
  return sum;
}

}  // namespace meshwave::metrics

#endif  // MESHWAVE_METRICS_TRIANGLE_BVH_H_
