#include "rasterizer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace meshwave::cli {
namespace {

Eigen::Matrix3d ViewRotation(const View& view) {
  const double a = view.azimuth_deg * std::numbers::pi / 180;
  const double e = view.elevation_deg * std::numbers::pi / 180;
  return (Eigen::AngleAxisd(e, Vec3::UnitX()) * Eigen::AngleAxisd(a, Vec3::UnitY()))
      .toRotationMatrix();
}

Framing FitEye(const std::vector<Vec3>& eye, const View& view) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Vec3& p : eye) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  if (eye.empty()) return Framing{};
  const double extent = std::max({hi.x() - lo.x(), hi.y() - lo.y(), 1e-300});
  return Framing{(lo + hi) / 2, 0.92 * std::min(view.width, view.height) / extent};
}

// Screen space: x, y in pixels (y down), depth growing towards the viewer.
std::vector<Vec3> ProjectToScreen(const std::vector<Vec3>& eye, const View& view) {
  const Framing f = view.framing ? *view.framing : FitEye(eye, view);
  const int w = view.width, h = view.height;
  std::vector<Vec3> s(eye.size());
  for (size_t i = 0; i < eye.size(); ++i) {
    s[i] = Vec3(w / 2.0 + (eye[i].x() - f.centre.x()) * f.pixels_per_unit,
                h / 2.0 - (eye[i].y() - f.centre.y()) * f.pixels_per_unit, eye[i].z());
  }
  return s;
}

std::vector<Vec3> ToEye(const TriMesh& mesh, const View& view) {
  const Eigen::Matrix3d rot = ViewRotation(view);
  // Eye space: x right, y up, z towards the viewer.
  std::vector<Vec3> eye(mesh.positions.size());
  for (size_t i = 0; i < eye.size(); ++i) eye[i] = rot * mesh.positions[i];
  return eye;
}

// Lambert light per vertex from area-weighted normals, with a quarter of
// ambient so faces turned away stay readable.
std::vector<double> VertexLight(const TriMesh& mesh, const std::vector<Vec3>& eye) {
  std::vector<Vec3> normal(eye.size(), Vec3::Zero());
  for (const Face& f : mesh.faces) {
    const Vec3 n = (eye[f[1]] - eye[f[0]]).cross(eye[f[2]] - eye[f[0]]);
    for (uint32_t v : f) normal[v] += n;
  }
  const Vec3 light = Vec3(0.3, 0.4, 1.0).normalized();
  std::vector<double> out(eye.size());
  for (size_t i = 0; i < eye.size(); ++i) {
    const double len = normal[i].norm();
    const double lambert = len > 0 ? std::fabs(normal[i].dot(light)) / len : 0.5;
    out[i] = 0.25 + 0.75 * lambert;
  }
  return out;
}

struct Target {
  int width, height;
  std::vector<uint8_t>& rgb;
  std::vector<double>& depth;
  std::vector<uint8_t>* covered;
};

void DrawFace(uint32_t face, const std::array<Vec3, 3>& v, const Vec3& light,
              const PixelShader& shade, Target& target) {
  const Vec3 &v0 = v[0], &v1 = v[1], &v2 = v[2];
  const double area = (v1.x() - v0.x()) * (v2.y() - v0.y()) - (v2.x() - v0.x()) * (v1.y() - v0.y());
  if (std::fabs(area) < 1e-12) return;
  const int w = target.width, h = target.height;
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
      if (z <= target.depth[at]) continue;
      const std::optional<Rgb8> colour = shade(face, Vec3(b0, b1, b2), light);
      if (!colour) continue;  // see-through: the depth stays for what lies behind
      target.depth[at] = z;
      if (target.covered) (*target.covered)[at] = 1;
      std::copy(colour->begin(), colour->end(), target.rgb.begin() + static_cast<ptrdiff_t>(at * 3));
    }
  }
}

}  // namespace

Framing FitFraming(const TriMesh& mesh, const View& view) {
  return FitEye(ToEye(mesh, view), view);
}

std::vector<uint8_t> Rasterize(const TriMesh& mesh, const PixelShader& shade, const View& view,
                               std::vector<uint8_t>* covered) {
  const int w = view.width, h = view.height;
  std::vector<uint8_t> rgb(static_cast<size_t>(w) * static_cast<size_t>(h) * 3, 255);
  if (covered) covered->assign(static_cast<size_t>(w) * static_cast<size_t>(h), 0);
  if (mesh.positions.empty()) return rgb;
  const std::vector<Vec3> eye = ToEye(mesh, view);
  const std::vector<Vec3> s = ProjectToScreen(eye, view);
  const std::vector<double> light = VertexLight(mesh, eye);

  std::vector<double> depth(static_cast<size_t>(w) * static_cast<size_t>(h),
                            -std::numeric_limits<double>::infinity());
  Target target{w, h, rgb, depth, covered};
  for (size_t i = 0; i < mesh.faces.size(); ++i) {
    const Face& f = mesh.faces[i];
    DrawFace(static_cast<uint32_t>(i), {s[f[0]], s[f[1]], s[f[2]]},
             Vec3(light[f[0]], light[f[1]], light[f[2]]), shade, target);
  }
  return rgb;
}

std::vector<uint8_t> Rasterize(const TriMesh& mesh, const std::vector<Vec3>& colours,
                               const View& view) {
  const PixelShader shade = [&](uint32_t face, const Vec3& b, const Vec3& light) {
    const Face& f = mesh.faces[face];
    // Lit at the corners, then interpolated: what the renders showed before
    // pixel shaders, to the bit.
    const Vec3 c = b[0] * Vec3(colours[f[0]] * light[0]) + b[1] * Vec3(colours[f[1]] * light[1]) +
                   b[2] * Vec3(colours[f[2]] * light[2]);
    Rgb8 out;
    for (int k = 0; k < 3; ++k) {
      // sRGB-ish gamma so the shading reads naturally.
      const double v = std::pow(std::clamp(c[k], 0.0, 1.0), 1 / 2.2);
      out[static_cast<size_t>(k)] = static_cast<uint8_t>(std::lround(255 * v));
    }
    return std::optional<Rgb8>(out);
  };
  return Rasterize(mesh, shade, view);
}

}  // namespace meshwave::cli
