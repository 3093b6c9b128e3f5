// Local frames of the coefficients of one level (Khodakovsky et al.
// 2000): for the odd
// vertex on edge (c1 -> c2) of M^j, n = normalised sum of the area-weighted
// normals of the edge's faces, t1 = the edge direction made orthogonal to
// n, t2 = n x t1. Built from level-j positions only, so the decoder can build
// the same frames before it reconstructs level j+1.
#ifndef MESHWAVE_WAVELET_LOCAL_FRAMES_H_
#define MESHWAVE_WAVELET_LOCAL_FRAMES_H_

#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "meshwave/mesh.h"
#include "meshwave/semiregular.h"

namespace meshwave {

// a . b summed as (x + y) + z: the order of Eigen's SSE2 code, which every
// x86-64 build runs, written out so that a build without it (WebAssembly:
// Eigen's scalar code sums x + (y + z)) rounds alike, to the bit.
inline double Dot3(const Vec3& a, const Vec3& b) {
  return (a.x() * b.x() + a.y() * b.y()) + a.z() * b.z();
}
inline double Norm3(const Vec3& v) { return std::sqrt(Dot3(v, v)); }

struct Frame {
  Vec3 n, t1, t2;  // orthonormal, right-handed
  Vec3 ToLocal(const Vec3& d) const { return {Dot3(d, n), Dot3(d, t1), Dot3(d, t2)}; }
  Vec3 ToGlobal(const Vec3& l) const { return l[0] * n + l[1] * t1 + l[2] * t2; }
};

// An orthonormal frame from a normal and a tangent hint; either may be zero
// or degenerate, then a world axis stands in (least aligned with the other).
// Inline: it runs once per coefficient in the transform's inner loops.
inline Frame MakeFrame(const Vec3& normal_hint, const Vec3& tangent_hint) {
  // The world axis least aligned with v (ties go to the lower axis).
  auto least_aligned_axis = [](const Vec3& v) -> Vec3 {
    const Vec3 a = v.cwiseAbs();
    if (a.x() <= a.y() && a.x() <= a.z()) return Vec3::UnitX();
    if (a.y() <= a.z()) return Vec3::UnitY();
    return Vec3::UnitZ();
  };
  // Normalises v in place; false when it is too short to carry a direction.
  auto normalize = [](Vec3& v) {
    const double len = Norm3(v);
    if (!(len > 1e-300) || !std::isfinite(len)) return false;
    v /= len;
    return true;
  };
  Frame f;
  f.n = normal_hint;
  f.t1 = tangent_hint;
  const bool has_n = normalize(f.n);
  bool has_t = normalize(f.t1);
  if (has_n && has_t) {
    f.t1 -= Dot3(f.t1, f.n) * f.n;
    has_t = Norm3(f.t1) > 1e-6 && normalize(f.t1);
  }
  if (!has_n) {
    if (!has_t) {
      f.n = Vec3::UnitZ();
      f.t1 = Vec3::UnitX();
      f.t2 = Vec3::UnitY();
      return f;
    }
    f.n = least_aligned_axis(f.t1);
    f.n -= Dot3(f.n, f.t1) * f.t1;
    f.n /= Norm3(f.n);  // Eigen's normalize(), nonzero here
  } else if (!has_t) {
    f.t1 = least_aligned_axis(f.n);
    f.t1 -= Dot3(f.t1, f.n) * f.n;
    f.t1 /= Norm3(f.t1);
  }
  f.t2 = f.n.cross(f.t1);
  return f;
}

// Face normals of the level being transformed; kept per thread so repeated
// transforms of large meshes do not allocate (and fault in) new pages. The
// forward and the inverse transform share it.
inline std::vector<Vec3>& FaceNormalScratch() {
  thread_local std::vector<Vec3> scratch;
  return scratch;
}

// Computes the frames of the coefficients of d^j one at a time from the
// level-j positions, without storing them (a million frames would be 72 MB).
// The face normals of level j are computed once, into `face_normals`, which
// callers keep between calls so large levels do not allocate afresh.
class LevelFrames {
 public:
  LevelFrames(const SemiRegularHierarchy& hierarchy, int j,
              std::span<const Vec3> positions, std::vector<Vec3>& face_normals)
      : edges_(hierarchy.edges(j)),
        edge_faces_(hierarchy.edge_faces(j)),
        x_(positions),
        normals_(face_normals) {
    const auto& faces = hierarchy.faces(j);
    face_normals.resize(faces.size());
    for (size_t f = 0; f < faces.size(); ++f) {
      const Vec3& p0 = x_[faces[f][0]];
      face_normals[f] = (x_[faces[f][1]] - p0).cross(x_[faces[f][2]] - p0);
    }
  }

  Frame operator()(uint32_t k) const {
    Vec3 n = normals_[edge_faces_[k][0]];
    if (edge_faces_[k][1] != SemiRegularHierarchy::kNone) {
      const Vec3 sum = n + normals_[edge_faces_[k][1]];
      // Two faces folded onto each other cancel: keep the first one's.
      if (Dot3(sum, sum) > 1e-12 * Dot3(n, n)) n = sum;
    }
    return MakeFrame(n, x_[edges_[k][1]] - x_[edges_[k][0]]);
  }

 private:
  const std::vector<Edge>& edges_;
  const std::vector<std::array<uint32_t, 2>>& edge_faces_;
  std::span<const Vec3> x_;
  const std::vector<Vec3>& normals_;
};

}  // namespace meshwave

#endif  // MESHWAVE_WAVELET_LOCAL_FRAMES_H_
