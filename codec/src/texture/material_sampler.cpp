#include "texture/material_sampler.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace meshwave {
namespace {

std::array<float, 256> MakeSrgbTable() {
  std::array<float, 256> table{};
  for (int i = 0; i < 256; ++i) {
    const double v = i / 255.0;
    table[static_cast<size_t>(i)] =
        static_cast<float>(v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4));
  }
  return table;
}

const std::array<float, 256>& SrgbTable() {
  static const std::array<float, 256> table = MakeSrgbTable();
  return table;
}

int64_t WrapIndex(int64_t i, int64_t n, WrapMode mode) {
  switch (mode) {
    case WrapMode::kClampToEdge:
      return std::clamp<int64_t>(i, 0, n - 1);
    case WrapMode::kMirroredRepeat: {
      const int64_t m = ((i % (2 * n)) + 2 * n) % (2 * n);
      return m < n ? m : 2 * n - 1 - m;
    }
    case WrapMode::kRepeat:
    default:
      return ((i % n) + n) % n;
  }
}

// Far beyond any texture's repeats, near enough that texel indices fit.
constexpr double kUvBound = 1e6;

}  // namespace

float SrgbByteToLinear(uint8_t value) { return SrgbTable()[value]; }

uint8_t LinearToSrgbByte(float linear) {
  const double v = std::clamp(static_cast<double>(linear), 0.0, 1.0);
  const double encoded = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055;
  return static_cast<uint8_t>(std::lround(std::clamp(encoded, 0.0, 1.0) * 255));
}

Eigen::Vector4f SampleImage(const AssetImage& image, WrapMode wrap_u, WrapMode wrap_v,
                            Eigen::Vector2f uv, bool srgb) {
  const int64_t width = image.width, height = image.height;
  if (image.rgba.size() != static_cast<size_t>(width * height * 4) || width == 0 || height == 0) {
    return Eigen::Vector4f::Ones();
  }
  const double u = std::isfinite(uv[0]) ? std::clamp<double>(uv[0], -kUvBound, kUvBound) : 0;
  const double v = std::isfinite(uv[1]) ? std::clamp<double>(uv[1], -kUvBound, kUvBound) : 0;
  const double x = u * static_cast<double>(width) - 0.5;
  const double y = v * static_cast<double>(height) - 0.5;
  const double fx = std::floor(x), fy = std::floor(y);
  const auto tx = static_cast<float>(x - fx), ty = static_cast<float>(y - fy);
  const auto ix = static_cast<int64_t>(fx), iy = static_cast<int64_t>(fy);
  const int64_t xs[2] = {WrapIndex(ix, width, wrap_u), WrapIndex(ix + 1, width, wrap_u)};
  const int64_t ys[2] = {WrapIndex(iy, height, wrap_v), WrapIndex(iy + 1, height, wrap_v)};
  const float wx[2] = {1 - tx, tx}, wy[2] = {1 - ty, ty};
  const std::array<float, 256>& table = SrgbTable();
  Eigen::Vector4f sum = Eigen::Vector4f::Zero();
  for (int b = 0; b < 2; ++b) {
    for (int a = 0; a < 2; ++a) {
      const uint8_t* texel = &image.rgba[static_cast<size_t>((ys[b] * width + xs[a]) * 4)];
      const float weight = wx[a] * wy[b];
      for (int c = 0; c < 3; ++c) {
        sum[c] += weight * (srgb ? table[texel[c]] : texel[c] / 255.0f);
      }
      sum[3] += weight * (texel[3] / 255.0f);
    }
  }
  return sum;
}

bool TriangleTangentFrame(const std::array<Vec3, 3>& p, const std::array<Eigen::Vector2d, 3>& uv,
                          TangentFrame& frame) {
  const Vec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
  const Vec3 n = e1.cross(e2);
  const double area2 = n.norm();
  if (!(area2 > 0)) return false;
  frame.normal = n / area2;
  const Eigen::Vector2d d1 = uv[1] - uv[0], d2 = uv[2] - uv[0];
  const double det = d1[0] * d2[1] - d2[0] * d1[1];
  // UV area below 1e-12 of the corners' spread: a line in texture space.
  const double scale = std::max({d1.squaredNorm(), d2.squaredNorm(), 1e-300});
  if (!(std::abs(det) > 1e-12 * scale) || !std::isfinite(det)) return false;
  const Vec3 dp_du = (e1 * d2[1] - e2 * d1[1]) / det;
  const Vec3 dp_dv = (e2 * d1[0] - e1 * d2[0]) / det;
  Vec3 t = dp_du - frame.normal * frame.normal.dot(dp_du);
  const double length = t.norm();
  if (!(length > 0) || !std::isfinite(length)) return false;
  t /= length;
  frame.tangent = t;
  frame.bitangent = frame.normal.cross(t);
  if (frame.bitangent.dot(dp_dv) < 0) frame.bitangent = -frame.bitangent;
  return true;
}

MaterialSampler::MaterialSampler(const MeshAsset& asset) : asset_(asset) {}

const Material& MaterialSampler::MaterialOf(uint32_t face) const {
  if (face < asset_.face_material.size() && asset_.face_material[face] < asset_.materials.size()) {
    return asset_.materials[asset_.face_material[face]];
  }
  return default_material_;
}

Eigen::Vector2f MaterialSampler::Uv(uint32_t face, const Vec3& w) const {
  if (asset_.uv.empty()) return Eigen::Vector2f::Zero();
  const Face& corners = asset_.uv.faces[face];
  Eigen::Vector2f uv = Eigen::Vector2f::Zero();
  for (int k = 0; k < 3; ++k) uv += static_cast<float>(w[k]) * asset_.uv.values[corners[k]];
  return uv;
}

Eigen::Vector2f MaterialSampler::TransformedUv(const TextureRef& ref, uint32_t face,
                                               int corner) const {
  const Eigen::Vector2f uv =
      asset_.uv.empty() ? Eigen::Vector2f::Zero() : asset_.uv.values[asset_.uv.faces[face][corner]];
  return ref.transform * Eigen::Vector3f(uv[0], uv[1], 1.0f);
}

Eigen::Vector4f MaterialSampler::Sample(const TextureRef& ref, uint32_t face, const Vec3& w,
                                        bool srgb) const {
  if (!ref.present() || static_cast<size_t>(ref.image) >= asset_.images.size()) {
    return Eigen::Vector4f::Ones();
  }
  const Eigen::Vector2f uv = Uv(face, w);
  const Eigen::Vector2f transformed = ref.transform * Eigen::Vector3f(uv[0], uv[1], 1.0f);
  return SampleImage(asset_.images[static_cast<size_t>(ref.image)], ref.wrap_u, ref.wrap_v,
                     transformed, srgb);
}

Eigen::Vector4f MaterialSampler::BaseColor(uint32_t face, const Vec3& w) const {
  const Material& m = MaterialOf(face);
  Eigen::Vector4f color =
      m.base_color_factor.cwiseProduct(Sample(m.base_color_texture, face, w, /*srgb=*/true));
  if (!asset_.color.empty()) {
    const Face& corners = asset_.color.faces[face];
    Eigen::Vector4f vertex = Eigen::Vector4f::Zero();
    for (int k = 0; k < 3; ++k) {
      vertex += static_cast<float>(w[k]) * asset_.color.values[corners[k]];
    }
    color = color.cwiseProduct(vertex);
  }
  switch (m.alpha_mode) {
    case AlphaMode::kOpaque:
      color[3] = 1;
      break;
    case AlphaMode::kMask:
      color[3] = color[3] >= m.alpha_cutoff ? 1.0f : 0.0f;
      break;
    case AlphaMode::kBlend:
      break;
  }
  return color.cwiseMax(0.0f).cwiseMin(1.0f);
}

Eigen::Vector3f MaterialSampler::OcclusionRoughnessMetallic(uint32_t face, const Vec3& w) const {
  const Material& m = MaterialOf(face);
  const Eigen::Vector4f mr = Sample(m.metallic_roughness_texture, face, w, /*srgb=*/false);
  const float occlusion =
      m.occlusion_texture.present()
          ? 1 + m.occlusion_strength * (Sample(m.occlusion_texture, face, w, false)[0] - 1)
          : 1.0f;
  return Eigen::Vector3f(occlusion, m.roughness_factor * mr[1], m.metallic_factor * mr[2])
      .cwiseMax(0.0f)
      .cwiseMin(1.0f);
}

Eigen::Vector3f MaterialSampler::Emissive(uint32_t face, const Vec3& w) const {
  const Material& m = MaterialOf(face);
  return m.emissive_factor.cwiseProduct(Sample(m.emissive_texture, face, w, true).head<3>());
}

Vec3 MaterialSampler::ObjectNormal(uint32_t face, const Vec3& w) const {
  const Material& m = MaterialOf(face);
  const Face& f = asset_.mesh.faces[face];
  const std::array<Vec3, 3> p = {asset_.mesh.positions[f[0]], asset_.mesh.positions[f[1]],
                                 asset_.mesh.positions[f[2]]};
  std::array<Eigen::Vector2d, 3> uv;
  for (int k = 0; k < 3; ++k) uv[k] = TransformedUv(m.normal_texture, face, k).cast<double>();
  TangentFrame frame;
  const bool usable = TriangleTangentFrame(p, uv, frame);
  if (!m.normal_texture.present() || !usable) return frame.normal;
  const Eigen::Vector4f texel = Sample(m.normal_texture, face, w, /*srgb=*/false);
  const Vec3 local(m.normal_scale * (2.0 * texel[0] - 1), m.normal_scale * (2.0 * texel[1] - 1),
                   2.0 * texel[2] - 1);
  const Vec3 n = local[0] * frame.tangent + local[1] * frame.bitangent + local[2] * frame.normal;
  const double length = n.norm();
  return length > 0 && std::isfinite(length) ? Vec3(n / length) : frame.normal;
}

}  // namespace meshwave
