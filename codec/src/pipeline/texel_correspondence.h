// Where each texel of the base-domain atlas comes from: the texel's centre
// is a point of a base face's triangle (gutter texels take the triangle's
// nearest point, so gutters repeat the edge and stay safe under mipmaps);
// its barycentric coordinates descend the 1-to-4 splits to a face of the
// remesh's finest level, whose point is projected onto the original
// surface (onto its nearest face turned the same way as the remesh's face,
// when one is nearly as near: thin parts have two sides close together).
// Every baked map samples the original there, so the geometric work is
// done once for all of them.
#ifndef MESHWAVE_PIPELINE_TEXEL_CORRESPONDENCE_H_
#define MESHWAVE_PIPELINE_TEXEL_CORRESPONDENCE_H_

#include <array>
#include <cstdint>
#include <vector>

#include "meshwave/mesh.h"
#include "meshwave/semiregular.h"
#include "metrics/triangle_bvh.h"
#include "texture/atlas_layout.h"

namespace meshwave {

// A point of the finest level: face index into hierarchy->faces(J) and
// barycentric coordinates in that face's corner order.
struct FinestPoint {
  uint32_t face = 0;
  Vec3 barycentric = Vec3::Zero();
};

// The point (b0, b1, b2) of `base_face` on level `levels` of the split
// pattern of semiregular.h: face f = (A, B, C) of level j has children
// 4f..4f+3 = (A, mAB, mCA), (B, mBC, mAB), (C, mCA, mBC), (mAB, mBC, mCA),
// so b0 >= 1/2 lies in child 0 at (2 b0 - 1, 2 b1, 2 b2), b1 >= 1/2 in
// child 1 at (2 b1 - 1, 2 b2, 2 b0), b2 >= 1/2 in child 2 at
// (2 b2 - 1, 2 b0, 2 b1), and the rest in child 3 at
// (1 - 2 b2, 1 - 2 b0, 1 - 2 b1). `b` is clamped to the triangle first.
FinestPoint DescendToFinest(int levels, uint32_t base_face, Vec3 b);

// The base face of a face of level `levels` and its corners' barycentric
// coordinates in that base face (the inverse of the descent's pattern).
struct BaseTriangle {
  uint32_t base_face = 0;
  std::array<Vec3, 3> corners;
};
BaseTriangle FinestFaceInBase(int levels, uint32_t finest_face);

// The base face whose triangle is nearest to the atlas point (x, y), ties
// to the even face of a cell, and the barycentric coordinates of that
// triangle's point nearest to it (the point itself inside the triangle).
// base_face is `layout.base_faces()` for points of cells no face uses.
struct AtlasOwner {
  uint32_t base_face = 0;
  Vec3 barycentric = Vec3::Zero();
};
AtlasOwner OwnerOfAtlasPoint(const AtlasLayout& layout, double x, double y);

// Where one texel samples the original: face index into the original's
// faces and its barycentric coordinates; the finest remesh face the texel
// lies on (for the normal map's frame). original_face is kNone for texels
// of cells no base face uses.
struct TexelSource {
  static constexpr uint32_t kNone = 0xffffffffu;
  uint32_t original_face = kNone;
  uint32_t finest_face = 0;
  float w1 = 0, w2 = 0;  // w0 = 1 - w1 - w2
};

// The correspondence between an atlas and an original surface through a
// remesh of it; immutable and safe to use from several threads.
class TexelCorrespondence {
 public:
  // The references must outlive this object. The original's faces index
  // its positions (checked by the caller: the asset readers guarantee it).
  TexelCorrespondence(const AtlasLayout& layout, const SemiRegularMesh& remesh,
                      const std::vector<Vec3>& original_positions,
                      const std::vector<Face>& original_faces, int threads);

  // The sources of the cell² texels of cell `cell_index` (row-major within
  // the cell) into `out`. Each cell's BVH queries are hinted only from
  // within the cell, so the result does not depend on which thread or in
  // what order cells are done.
  void Cell(uint32_t cell_index, std::vector<TexelSource>& out) const;

  // The source of one atlas point (texel coordinates).
  TexelSource AtPoint(double x, double y, uint32_t& hint) const;

 private:
  // Whether the original face turns the way `normal` does (not away).
  bool FacesAlike(uint32_t original_face, const Vec3& normal) const;

  const AtlasLayout& layout_;
  const SemiRegularMesh& remesh_;
  const std::vector<Vec3>& original_positions_;
  const std::vector<Face>& original_faces_;
  metrics::TriangleBvh bvh_;
};

}  // namespace meshwave

#endif  // MESHWAVE_PIPELINE_TEXEL_CORRESPONDENCE_H_
