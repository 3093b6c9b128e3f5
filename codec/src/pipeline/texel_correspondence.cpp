#include "pipeline/texel_correspondence.h"

#include <algorithm>
#include <cmath>

#include "pipeline/color_transfer.h"

namespace meshwave {
namespace {

// The barycentric coordinates clamped into the triangle (rounding, or a
// caller's point just outside) and summing to 1.
Vec3 ClampToTriangle(Vec3 b) {
  b = b.cwiseMax(0.0);
  const double sum = b.sum();
  if (!(sum > 0)) return Vec3::Constant(1.0 / 3.0);
  return b / sum;
}

// The corners of child `k` given the parent's corners, in the order of the
// split pattern (semiregular.h).
std::array<Vec3, 3> ChildCorners(const std::array<Vec3, 3>& p, uint32_t k) {
  const Vec3 ab = 0.5 * (p[0] + p[1]), bc = 0.5 * (p[1] + p[2]), ca = 0.5 * (p[2] + p[0]);
  switch (k) {
    case 0:
      return {p[0], ab, ca};
    case 1:
      return {p[1], bc, ab};
    case 2:
      return {p[2], ca, bc};
    default:
      return {ab, bc, ca};
  }
}

}  // namespace

FinestPoint DescendToFinest(int levels, uint32_t base_face, Vec3 b) {
  b = ClampToTriangle(b);
  uint32_t face = base_face;
  for (int j = 0; j < levels; ++j) {
    uint32_t child;
    Vec3 c;
    if (b[0] >= 0.5) {
      child = 0;
      c = {2 * b[0] - 1, 2 * b[1], 2 * b[2]};
    } else if (b[1] >= 0.5) {
      child = 1;
      c = {2 * b[1] - 1, 2 * b[2], 2 * b[0]};
    } else if (b[2] >= 0.5) {
      child = 2;
      c = {2 * b[2] - 1, 2 * b[0], 2 * b[1]};
    } else {
      child = 3;
      c = {1 - 2 * b[2], 1 - 2 * b[0], 1 - 2 * b[1]};
    }
    // Doubling doubles rounding too: clamp so it never leaves the face.
    b = ClampToTriangle(c);
    face = 4 * face + child;
  }
  return {face, b};
}

BaseTriangle FinestFaceInBase(int levels, uint32_t finest_face) {
  BaseTriangle out;
  out.base_face = finest_face >> (2 * levels);
  out.corners = {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  for (int j = levels - 1; j >= 0; --j) {
    out.corners = ChildCorners(out.corners, (finest_face >> (2 * j)) & 3u);
  }
  return out;
}

AtlasOwner OwnerOfAtlasPoint(const AtlasLayout& layout, double x, double y) {
  const uint32_t cell = layout.cell();
  const auto column = static_cast<uint32_t>(std::clamp(x / cell, 0.0, layout.columns() - 1.0));
  const auto row = static_cast<uint32_t>(std::clamp(y / cell, 0.0, layout.rows() - 1.0));
  const uint32_t first = 2 * (row * layout.columns() + column);
  AtlasOwner best{layout.base_faces(), Vec3::Constant(1.0 / 3.0)};
  double best_distance = std::numeric_limits<double>::infinity();
  const Vec3 p(x, y, 0);
  for (uint32_t f = first; f < std::min(first + 2, layout.base_faces()); ++f) {
    const auto t = layout.Triangle(f);
    const Vec3 a(t[0].x, t[0].y, 0), b(t[1].x, t[1].y, 0), c(t[2].x, t[2].y, 0);
    const Vec3 w = ClosestBarycentric(p, a, b, c);
    const double distance = (w[0] * a + w[1] * b + w[2] * c - p).squaredNorm();
    if (distance < best_distance) {
      best_distance = distance;
      best = {f, w};
    }
  }
  return best;
}

TexelCorrespondence::TexelCorrespondence(const AtlasLayout& layout, const SemiRegularMesh& remesh,
                                         const std::vector<Vec3>& original_positions,
                                         const std::vector<Face>& original_faces, int threads)
    : layout_(layout),
      remesh_(remesh),
      original_positions_(original_positions),
      original_faces_(original_faces),
      bvh_(original_positions, original_faces, threads) {}

TexelSource TexelCorrespondence::AtPoint(double x, double y, uint32_t& hint) const {
  TexelSource source;
  const AtlasOwner owner = OwnerOfAtlasPoint(layout_, x, y);
  if (owner.base_face >= layout_.base_faces()) return source;
  const int levels = remesh_.levels();
  const FinestPoint fine = DescendToFinest(levels, owner.base_face, owner.barycentric);
  const Face& corners = remesh_.hierarchy->faces(levels)[fine.face];
  const Vec3 point = fine.barycentric[0] * remesh_.positions[corners[0]] +
                     fine.barycentric[1] * remesh_.positions[corners[1]] +
                     fine.barycentric[2] * remesh_.positions[corners[2]];
  metrics::TriangleBvh::Hit hit = bvh_.ClosestPoint(point, hint);
  const Vec3& a = remesh_.positions[corners[0]];
  const Vec3& b = remesh_.positions[corners[1]];
  const Vec3& c = remesh_.positions[corners[2]];
  const Vec3 normal = (b - a).cross(c - a);
  if (hit.face != metrics::TriangleBvh::kNoFace && !FacesAlike(hit.face, normal)) {
    // The nearest point is on a face turned away: on a thin part (a shell's
    // rim, a sheet's two sides) the other side may be nearer than the side
    // the remesh face stands for. Take the nearest face turned the same way
    // if it is within a finest edge's length more.
    const double reach =
        std::sqrt(hit.distance_squared) +
        std::sqrt(std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()}));
    const metrics::TriangleBvh::Hit alike = bvh_.ClosestPointIf(
        point, metrics::TriangleBvh::kNoFace,
        [&](uint32_t face) { return FacesAlike(face, normal); }, reach * reach);
    if (alike.face != metrics::TriangleBvh::kNoFace) hit = alike;
  }
  hint = hit.face;
  source.finest_face = fine.face;
  if (hit.face == metrics::TriangleBvh::kNoFace) return source;
  const Face& f = original_faces_[hit.face];
  const Vec3 w = ClosestBarycentric(hit.point, original_positions_[f[0]], original_positions_[f[1]],
                                    original_positions_[f[2]]);
  source.original_face = hit.face;
  source.w1 = static_cast<float>(w[1]);
  source.w2 = static_cast<float>(w[2]);
  return source;
}

bool TexelCorrespondence::FacesAlike(uint32_t original_face, const Vec3& normal) const {
  const Face& f = original_faces_[original_face];
  const Vec3& p0 = original_positions_[f[0]];
  return (original_positions_[f[1]] - p0).cross(original_positions_[f[2]] - p0).dot(normal) >= 0;
}

void TexelCorrespondence::Cell(uint32_t cell_index, std::vector<TexelSource>& out) const {
  const uint32_t cell = layout_.cell();
  const double x0 = static_cast<double>((cell_index % layout_.columns()) * cell);
  const double y0 = static_cast<double>((cell_index / layout_.columns()) * cell);
  out.resize(size_t{cell} * cell);
  uint32_t hint = metrics::TriangleBvh::kNoFace;
  for (uint32_t j = 0; j < cell; ++j) {
    // Rows alternate direction so each query's hint is its neighbour's face.
    const bool reverse = (j % 2) == 1;
    for (uint32_t step = 0; step < cell; ++step) {
      const uint32_t i = reverse ? cell - 1 - step : step;
      out[size_t{j} * cell + i] = AtPoint(x0 + i + 0.5, y0 + j + 0.5, hint);
    }
  }
}

}  // namespace meshwave
