// The original asset's appearance at a point of its surface (a face and
// barycentric coordinates): each material channel as glTF 2.0's
// metallic-roughness model defines it, the texture sampled bilinearly at
// the point's interpolated UV (after the slot's UV transform, with its wrap
// modes) and multiplied by the material's factors and, for base colour, the
// vertex colour.
#ifndef MESHWAVE_TEXTURE_MATERIAL_SAMPLER_H_
#define MESHWAVE_TEXTURE_MATERIAL_SAMPLER_H_

#include <Eigen/Core>
#include <array>
#include <cstdint>

#include "meshwave/mesh.h"
#include "meshwave/mesh_asset.h"

namespace meshwave {

// sRGB-encoded 8-bit values to linear, and linear back to the nearest 8-bit
// sRGB value (IEC 61966-2-1).
float SrgbByteToLinear(uint8_t value);
uint8_t LinearToSrgbByte(float linear);

// Bilinear sample of `image` at `uv` (glTF's convention: (0, 0) the
// top-left corner of the image) with the slot's wrap modes, the texel
// centres at ((i + 0.5) / width, (j + 0.5) / height). With `srgb` the RGB
// samples are decoded to linear before they are interpolated; alpha is
// always linear. An image without pixels samples white.
Eigen::Vector4f SampleImage(const AssetImage& image, WrapMode wrap_u, WrapMode wrap_v,
                            Eigen::Vector2f uv, bool srgb);

class MaterialSampler {
 public:
  // `asset` must outlive the sampler; its indices are a reader's (in range).
  explicit MaterialSampler(const MeshAsset& asset);

  const Material& MaterialOf(uint32_t face) const;
  // The face's interpolated texture coordinates (before any transform);
  // (0, 0) when the asset has none.
  Eigen::Vector2f Uv(uint32_t face, const Vec3& w) const;

  // Linear RGBA: factor x texture x vertex colour. Alpha is 1 for opaque
  // materials and 0 or 1 by the cutoff for masked ones.
  Eigen::Vector4f BaseColor(uint32_t face, const Vec3& w) const;
  // (occlusion, roughness, metallic) as glTF packs them in R, G, B, each
  // with its factor (occlusion: 1 + strength (texture - 1)).
  Eigen::Vector3f OcclusionRoughnessMetallic(uint32_t face, const Vec3& w) const;
  // Linear RGB: factor x texture.
  Eigen::Vector3f Emissive(uint32_t face, const Vec3& w) const;
  // The shading normal the normal map gives, in object space (unit): the
  // map's tangent-space normal (xy scaled by normal_scale) through the
  // face's tangent frame from its positions and UVs. The face's normal
  // where the material has no normal map or the face's UVs are degenerate.
  Vec3 ObjectNormal(uint32_t face, const Vec3& w) const;

 private:
  Eigen::Vector4f Sample(const TextureRef& ref, uint32_t face, const Vec3& w, bool srgb) const;
  Eigen::Vector2f TransformedUv(const TextureRef& ref, uint32_t face, int corner) const;

  const MeshAsset& asset_;
  Material default_material_;
};

// An orthonormal tangent frame of a triangle with texture coordinates:
// tangent along increasing u, bitangent cross(normal, tangent) times the
// handedness that makes it point along increasing v. False (frame
// unusable) for a degenerate triangle or degenerate UVs.
struct TangentFrame {
  Vec3 tangent = Vec3::UnitX();
  Vec3 bitangent = Vec3::UnitY();
  Vec3 normal = Vec3::UnitZ();
};
bool TriangleTangentFrame(const std::array<Vec3, 3>& p, const std::array<Eigen::Vector2d, 3>& uv,
                          TangentFrame& frame);

}  // namespace meshwave

#endif  // MESHWAVE_TEXTURE_MATERIAL_SAMPLER_H_
