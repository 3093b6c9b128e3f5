#include "rasterizer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace meshwave::cli {

std::vector<uint8_t> Rasterize(const TriMesh& mesh, const std::vector<Vec3>& colours,
                               const View& view) {
  const int w = view.width, h = view.height;
  std::vector<uint8_t> rgb(static_cast<size_t>(w) * static_cast<size_t>(h) * 3, 255);
  if (mesh.positions.empty()) return rgb;
  const double a = view.azimuth_deg * std::numbers::pi / 180;
  const double e = view.elevation_deg * std::numbers::pi / 180;
  const Eigen::Matrix3d rot =
      (Eigen::AngleAxisd(e, Vec3::UnitX()) * Eigen::AngleAxisd(a, Vec3::UnitY())).toRotationMatrix();

  // Eye space: x right, y up, z towards the viewer.
  std::vector<Vec3> p(mesh.positions.size());
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (size_t i = 0; i < p.size(); ++i) {
    p[i] = rot * mesh.positions[i];
    lo = lo.cwiseMin(p[i]);
    hi = hi.cwiseMax(p[i]);
  }
  const double extent = std::max({hi.x() - lo.x(), hi.y() - lo.y(), 1e-300});
  const double scale = 0.92 * std::min(w, h) / extent;
  const Vec3 centre = (lo + hi) / 2;
  std::vector<Vec3> s(p.size());  // screen: x, y in pixels (y down), depth
  for (size_t i = 0; i < p.size(); ++i) {
    s[i] = Vec3(w / 2.0 + (p[i].x() - centre.x()) * scale,
                h / 2.0 - (p[i].y() - centre.y()) * scale, p[i].z());
  }

  // Vertex normals (area-weighted) for Gouraud shading.
  std::vector<Vec3> normal(p.size(), Vec3::Zero());
  for (const Face& f : mesh.faces) {
    const Vec3 n = (p[f[1]] - p[f[0]]).cross(p[f[2]] - p[f[0]]);
    for (uint32_t v : f) normal[v] += n;
  }
  const Vec3 light = Vec3(0.3, 0.4, 1.0).normalized();
  std::vector<Vec3> shaded(p.size());
  for (size_t i = 0; i < p.size(); ++i) {
    const double len = normal[i].norm();
    const double lambert = len > 0 ? std::fabs(normal[i].dot(light)) / len : 0.5;
    shaded[i] = colours[i] * (0.25 + 0.75 * lambert);
  }

  std::vector<double> depth(static_cast<size_t>(w) * static_cast<size_t>(h),
                            -std::numeric_limits<double>::infinity());
  for (const Face& f : mesh.faces) {
    const Vec3 &v0 = s[f[0]], &v1 = s[f[1]], &v2 = s[f[2]];
    const double area = (v1.x() - v0.x()) * (v2.y() - v0.y()) - (v2.x() - v0.x()) * (v1.y() - v0.y());
    if (std::fabs(area) < 1e-12) continue;
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({v0.x(), v1.x(), v2.x()}))));
    const int x1 = std::min(w - 1, static_cast<int>(std::ceil(std::max({v0.x(), v1.x(), v2.x()}))));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({v0.y(), v1.y(), v2.y()}))));
    const int y1 = std::min(h - 1, static_cast<int>(std::ceil(std::max({v0.y(), v1.y(), v2.y()}))));
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const double px = x + 0.5, py = y + 0.5;
        // Barycentric coordinates from edge functions.
        const double b0 = ((v1.x() - px) * (v2.y() - py) - (v2.x() - px) * (v1.y() - py)) / area;
        const double b1 = ((v2.x() - px) * (v0.y() - py) - (v0.x() - px) * (v2.y() - py)) / area;
        const double b2 = 1 - b0 - b1;
        if (b0 < 0 || b1 < 0 || b2 < 0) continue;
        const double z = b0 * v0.z() + b1 * v1.z() + b2 * v2.z();
        const size_t at = static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x);
        if (z <= depth[at]) continue;
        depth[at] = z;
        const Vec3 c = b0 * shaded[f[0]] + b1 * shaded[f[1]] + b2 * shaded[f[2]];
        for (int k = 0; k < 3; ++k) {
          // sRGB-ish gamma so the shading reads naturally.
          const double v = std::pow(std::clamp(c[k], 0.0, 1.0), 1 / 2.2);
          rgb[at * 3 + static_cast<size_t>(k)] = static_cast<uint8_t>(std::lround(255 * v));
        }
      }
    }
  }
  return rgb;
}

}  // namespace meshwave::cli
