// The input surface the remesher fits to: its triangles in a BVH, their unit
// normals and components, and its boundary loops.
#ifndef MESHWAVE_REMESH_INPUT_SURFACE_H_
#define MESHWAVE_REMESH_INPUT_SURFACE_H_

#include <cstdint>
#include <limits>
#include <vector>

#include "meshwave/mesh.h"
#include "metrics/triangle_bvh.h"
#include "remesh/boundary_loops.h"
#include "remesh/components.h"

namespace meshwave::remesh {

class InputSurface {
 public:
  static constexpr uint32_t kNoFace = metrics::TriangleBvh::kNoFace;

  // `mesh` must be an oriented manifold; `components` labels it. Both are
  // kept by value; the object is immutable and safe to query from several
  // threads.
  InputSurface(TriMesh mesh, Components components);
  InputSurface(const InputSurface&) = delete;
  InputSurface& operator=(const InputSurface&) = delete;

  const TriMesh& mesh() const { return mesh_; }
  const Components& components() const { return components_; }
  const BoundaryLoops& loops() const { return loops_; }
  // Unit normal of face f, zero when the face has no area.
  const Vec3& FaceNormal(uint32_t f) const { return normals_[f]; }
  double diagonal() const { return diagonal_; }

  struct Projection {
    Vec3 point = Vec3::Zero();
    uint32_t face = kNoFace;  // kNoFace: nothing found
    bool found() const { return face != kNoFace; }
  };

  // Where the line through q along n first meets (smallest |t|, either
  // side, |t| <= reach·|n|) a face of `component` that faces the way n does
  // (positive dot product): how normal meshes place a new vertex.
  Projection AlongNormal(const Vec3& q, const Vec3& n, double reach,
                         uint32_t component) const;

  // The closest point of `component` among its faces whose normal is within
  // about 85° of n (any face when n is zero) and that are nearer than
  // max_distance. Facing the right way keeps a vertex on its own sheet
  // where two sheets are close (thin parts); the bound keeps it from
  // jumping to a far part of the surface when no face nearby faces n.
  Projection Closest(
      const Vec3& q, const Vec3& n, uint32_t component, uint32_t hint,
      double max_distance = std::numeric_limits<double>::infinity()) const;

  // The closest point of `component` among its faces whose unit normal m
  // has m·n > min_dot (n of any length; every face when n is zero).
  Projection ClosestWithin(const Vec3& q, const Vec3& n, double min_dot,
                           uint32_t component, uint32_t hint) const;

  // Whether `point` (on face `face`) lies on a boundary edge of the input,
  // to within 1e-9 of the edge's length.
  bool OnBoundary(const Vec3& point, uint32_t face) const;

  // The closest point over all faces, as a measurement would find it.
  Projection ClosestAnywhere(const Vec3& q, uint32_t hint) const;

 private:
  TriMesh mesh_;
  Components components_;
  std::vector<Vec3> normals_;
  std::vector<uint8_t> boundary_edges_;  // per face, bit i: edge i -> i+1
  metrics::TriangleBvh bvh_;
  BoundaryLoops loops_;
  double diagonal_ = 0;
};

}  // namespace meshwave::remesh

#endif  // MESHWAVE_REMESH_INPUT_SURFACE_H_
