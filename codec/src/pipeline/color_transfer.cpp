#include "pipeline/color_transfer.h"

#include <algorithm>
#include <string>

#include "core/parallel_for.h"
#include "metrics/closest_point_triangle.h"
#include "metrics/triangle_bvh.h"

namespace meshwave {

namespace {

// Queries are hinted with the face found for the previous target of the
// same block; blocks of a fixed size (not the threads' chunks) keep the
// face chosen among equally near ones, and so the colour, independent of
// the thread count.
constexpr size_t kBlock = 256;

Status CheckColors(const std::vector<Vec3>& positions, const std::vector<Face>& faces,
                   const CornerAttribute<Eigen::Vector4f>& color) {
  if (faces.empty()) return InvalidArgument("colour transfer: the original surface has no face");
  if (color.empty()) return InvalidArgument("colour transfer: the original has no vertex colours");
  if (color.faces.size() != faces.size()) {
    return InvalidArgument("colour transfer: " + std::to_string(color.faces.size()) +
                           " colour corner triples for " + std::to_string(faces.size()) +
                           " faces");
  }
  for (size_t f = 0; f < faces.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      if (faces[f][k] >= positions.size() || color.faces[f][k] >= color.values.size()) {
        return InvalidArgument("colour transfer: face " + std::to_string(f) +
                               " indexes past the positions or colours");
      }
    }
  }
  return Status::Ok();
}

// Non-finite points would find no nearest face.
Status CheckFinite(const std::vector<Vec3>& points, const char* what) {
  for (size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) {
      return InvalidArgument(std::string("colour transfer: ") + what + " " + std::to_string(i) +
                             " is not finite");
    }
  }
  return Status::Ok();
}

}  // namespace

Vec3 ClosestBarycentric(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 e0 = b - a;
  const Vec3 e1 = c - a;
  const double d00 = e0.squaredNorm();
  const double d01 = e0.dot(e1);
  const double d11 = e1.squaredNorm();
  const double denominator = d00 * d11 - d01 * d01;
  // sin² of the angle at a below 1e-12: the solve below would divide by
  // rounding noise.
  if (!(denominator > 1e-12 * d00 * d11)) {
    // Collinear corners: the triangle is its longest edge.
    const Vec3* corner[3] = {&a, &b, &c};
    int from = 0;
    double longest = -1;
    for (int k = 0; k < 3; ++k) {
      const double length = (*corner[(k + 1) % 3] - *corner[k]).squaredNorm();
      if (length > longest) {
        longest = length;
        from = k;
      }
    }
    if (!(longest > 0)) return Vec3::Constant(1.0 / 3.0);
    const Vec3& u = *corner[from];
    const Vec3& v = *corner[(from + 1) % 3];
    const double t = std::clamp((p - u).dot(v - u) / longest, 0.0, 1.0);
    Vec3 w = Vec3::Zero();
    w[from] = 1 - t;
    w[(from + 1) % 3] = t;
    return w;
  }
  const Vec3 q = metrics::ClosestPointOnTriangle(p, a, b, c).point - a;
  const double d20 = q.dot(e0);
  const double d21 = q.dot(e1);
  Vec3 w;
  w[1] = std::clamp((d11 * d20 - d01 * d21) / denominator, 0.0, 1.0);
  w[2] = std::clamp((d00 * d21 - d01 * d20) / denominator, 0.0, 1.0);
  // q lies in the triangle; clamping only removes rounding, so w1 + w2
  // exceeds 1 by rounding at most.
  const double sum = w[1] + w[2];
  if (sum > 1) w.tail<2>() /= sum;
  w[0] = 1 - w[1] - w[2];
  return w;
}

Result<std::vector<Vec3>> TransferCornerColors(const std::vector<Vec3>& positions,
                                               const std::vector<Face>& faces,
                                               const CornerAttribute<Eigen::Vector4f>& color,
                                               const std::vector<Vec3>& targets, int threads) {
  MW_RETURN_IF_ERROR(CheckColors(positions, faces, color));
  MW_RETURN_IF_ERROR(CheckFinite(positions, "original vertex"));
  MW_RETURN_IF_ERROR(CheckFinite(targets, "target"));
  const metrics::TriangleBvh bvh(positions, faces, threads);
  std::vector<Vec3> out(targets.size());
  const size_t blocks = (targets.size() + kBlock - 1) / kBlock;
  ParallelFor(
      blocks, threads,
      [&](size_t first, size_t last) {
        for (size_t block = first; block < last; ++block) {
          uint32_t hint = metrics::TriangleBvh::kNoFace;
          const size_t end = std::min(targets.size(), (block + 1) * kBlock);
          for (size_t i = block * kBlock; i < end; ++i) {
            const metrics::TriangleBvh::Hit hit = bvh.ClosestPoint(targets[i], hint);
            hint = hit.face;
            const Face& f = faces[hit.face];
            const Vec3 w = ClosestBarycentric(hit.point, positions[f[0]], positions[f[1]],
                                              positions[f[2]]);
            const Face& corners = color.faces[hit.face];
            Vec3 rgb = Vec3::Zero();
            for (int k = 0; k < 3; ++k) {
              rgb += w[k] * color.values[corners[k]].head<3>().cast<double>();
            }
            out[i] = rgb;
          }
        }
      },
      /*min_chunk=*/16);
  return out;
}

}  // namespace meshwave
