// Texture baking: the descent from a base face to the finest level, gutter
// texels repeating their triangle's edge, baked texels equal to the
// original's texture at the corresponding surface point (through our own
// decoder), normals carried into the atlas's tangent frame, pyramid sizes,
// independence of the thread count, and no bake for an asset without
// textures.
#include "meshwave/texture_bake.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "../metrics/test_meshes_testonly.h"
#include "image/image_decoder.h"
#include "meshwave/subdivision.h"
#include "pipeline/color_transfer.h"
#include "pipeline/texel_correspondence.h"
#include "test_data.h"
#include "texture/atlas_layout.h"
#include "texture/material_sampler.h"

namespace meshwave {
namespace {

MeshAsset Die() {
  auto asset = ReadMeshAsset(testing::SampleMesh("textured/die.obj"));
  EXPECT_TRUE(asset.ok()) << asset.status().ToString();
  return asset.ok() ? std::move(*asset) : MeshAsset{};
}

// The die refined by midpoint splits: its finest surface is the die's own.
SemiRegularMesh Refined(const TriMesh& mesh, int levels) {
  auto refined = Subdivide(mesh, levels, SubdivisionScheme::kMidpoint);
  EXPECT_TRUE(refined.ok()) << refined.status().ToString();
  return std::move(*refined);
}

DecodedImage Decode(const std::string& bytes) {
  auto image = DecodeImage(bytes, {}, "baked");
  EXPECT_TRUE(image.ok()) << image.status().ToString();
  return image.ok() ? std::move(*image) : DecodedImage{};
}

const TextureMap* FindMap(const BakedTexture& texture, TextureRole role) {
  for (const TextureMap& map : texture.maps) {
    if (map.role == role) return &map;
  }
  return nullptr;
}

Vec3 PointOf(const SemiRegularMesh& mesh, int level, uint32_t face, const Vec3& b) {
  const Face& f = mesh.hierarchy->faces(level)[face];
  return b[0] * mesh.positions[f[0]] + b[1] * mesh.positions[f[1]] + b[2] * mesh.positions[f[2]];
}

TEST(TextureBakeTest, DescendsToTheFinestFaceThePointLiesOn) {
  // Midpoint refinement keeps the base faces flat, so the base point and
  // the finest point must coincide.
  const SemiRegularMesh mesh = Refined(testing::Icosphere(0), 4);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto base_faces = static_cast<uint32_t>(mesh.hierarchy->faces(0).size());
  for (int i = 0; i < 2000; ++i) {
    const uint32_t f = static_cast<uint32_t>(rng() % base_faces);
    Vec3 b(unit(rng), unit(rng), unit(rng));
    if (i % 10 == 0) b[i % 3] = 0;  // points on edges too
    b /= b.sum();
    const FinestPoint fine = DescendToFinest(4, f, b);
    ASSERT_LT(fine.face, mesh.hierarchy->faces(4).size());
    EXPECT_GE(fine.barycentric.minCoeff(), 0.0);
    EXPECT_NEAR(fine.barycentric.sum(), 1.0, 1e-12);
    EXPECT_LT((PointOf(mesh, 4, fine.face, fine.barycentric) - PointOf(mesh, 0, f, b)).norm(),
              1e-12)
        << "base face " << f;
    // The inverse: the finest face's corners in base coordinates.
    const BaseTriangle base = FinestFaceInBase(4, fine.face);
    EXPECT_EQ(base.base_face, f);
    const Vec3 back = fine.barycentric[0] * base.corners[0] +
                      fine.barycentric[1] * base.corners[1] + fine.barycentric[2] * base.corners[2];
    EXPECT_LT((back - b).norm(), 1e-12);
  }
}

TEST(TextureBakeTest, GutterTexelsTakeTheNearestPointOfTheirTriangle) {
  auto layout = AtlasLayout::Create(5, 32, 4);
  ASSERT_TRUE(layout.ok());
  for (uint32_t y = 0; y < layout->height(); ++y) {
    for (uint32_t x = 0; x < layout->width(); ++x) {
      const AtlasOwner owner = OwnerOfAtlasPoint(*layout, x + 0.5, y + 0.5);
      if (owner.base_face >= 5) continue;  // the unused half of the last cell
      // The owner's triangle is the nearest one and the point its nearest.
      const AtlasPoint q = layout->Map(owner.base_face, owner.barycentric[0], owner.barycentric[1],
                                       owner.barycentric[2]);
      const double d = std::hypot(q.x - x - 0.5, q.y - y - 0.5);
      ASSERT_EQ(owner.base_face / 2, (y / 32) * layout->columns() + x / 32);
      if (d > 1e-9) {
        // Outside the triangle: on its border, and no nearer to the other.
        EXPECT_NEAR(owner.barycentric.minCoeff(), 0.0, 1e-12);
        const uint32_t other = owner.base_face ^ 1u;
        if (other < 5) {
          const auto t = layout->Triangle(other);
          const Vec3 p(x + 0.5, y + 0.5, 0), a(t[0].x, t[0].y, 0), b(t[1].x, t[1].y, 0),
              c(t[2].x, t[2].y, 0);
          const Vec3 w = ClosestBarycentric(p, a, b, c);
          EXPECT_GE((w[0] * a + w[1] * b + w[2] * c - p).norm(), d - 1e-9);
        }
      }
    }
  }
}

TEST(TextureBakeTest, BakedTexelsMatchTheOriginalTextureAndGuttersRepeatEdges) {
  const MeshAsset die = Die();
  const SemiRegularMesh mesh = Refined(die.mesh, 1);
  TextureBakeOptions options;
  options.quality = 100;
  options.threads = 2;
  auto baked = BakeTexture(die, mesh, options);
  ASSERT_TRUE(baked.ok()) << baked.status().ToString();
  ASSERT_TRUE(baked->has_value());
  const BakedTexture& texture = **baked;
  ASSERT_EQ(texture.maps.size(), 1u);  // base colour only: the die has no other map
  const TextureMap& map = texture.maps[0];
  EXPECT_EQ(map.role, TextureRole::kBaseColor);
  EXPECT_EQ(map.mime_type, "image/webp");
  const DecodedImage image = Decode(map.levels.back());
  auto layout =
      AtlasLayout::Create(static_cast<uint32_t>(mesh.hierarchy->faces(0).size()),
                          texture.atlas.cell, texture.atlas.gutter, texture.atlas.columns);
  ASSERT_TRUE(layout.ok());
  ASSERT_EQ(image.width, layout->width());
  ASSERT_EQ(image.height, layout->height());

  // Texels inside triangles against the die's texture at the same point of
  // the surface, found here by brute force over the original's faces.
  const MaterialSampler sampler(die);
  const AssetImage& original = die.images[0];
  std::mt19937 rng(11);
  std::vector<double> errors;
  for (int tries = 0; errors.size() < 1200 && tries < 100000; ++tries) {
    const uint32_t x = rng() % image.width, y = rng() % image.height;
    const AtlasOwner owner = OwnerOfAtlasPoint(*layout, x + 0.5, y + 0.5);
    if (owner.base_face >= layout->base_faces() || owner.barycentric.minCoeff() < 0.05) continue;
    const Vec3 p = PointOf(mesh, 0, owner.base_face, owner.barycentric);
    uint32_t nearest = 0;
    Vec3 nearest_w;
    double best = 1e300;
    for (uint32_t f = 0; f < die.mesh.faces.size(); ++f) {
      const Face& c = die.mesh.faces[f];
      const Vec3 w = ClosestBarycentric(p, die.mesh.positions[c[0]], die.mesh.positions[c[1]],
                                        die.mesh.positions[c[2]]);
      const double d = (w[0] * die.mesh.positions[c[0]] + w[1] * die.mesh.positions[c[1]] +
                        w[2] * die.mesh.positions[c[2]] - p)
                           .squaredNorm();
      if (d < best) {
        best = d;
        nearest = f;
        nearest_w = w;
      }
    }
    const Material& m = sampler.MaterialOf(nearest);
    const Eigen::Vector4f expected =
        SampleImage(original, m.base_color_texture.wrap_u, m.base_color_texture.wrap_v,
                    sampler.Uv(nearest, nearest_w), /*srgb=*/true);
    const uint8_t* got = &image.rgba[(size_t{y} * image.width + x) * 4];
    for (int c = 0; c < 3; ++c) {
      errors.push_back(std::abs(static_cast<double>(got[c]) - LinearToSrgbByte(expected[c])));
    }
  }
  ASSERT_GE(errors.size(), 1200u);
  std::sort(errors.begin(), errors.end());
  double mean = 0;
  for (double e : errors) mean += e / static_cast<double>(errors.size());
  // WebP at quality 100 with 4:2:0 chroma: small errors, larger only at
  // the pips' sharp colour edges.
  EXPECT_LT(mean, 3.0);
  EXPECT_LT(errors[errors.size() * 9 / 10], 8.0);

  // A gutter texel repeats the triangle texel its nearest point lies in
  // (within WebP's error: the codec smooths across the gutter's border too).
  int gutter_texels = 0;
  double gutter_error = 0;
  for (uint32_t y = 0; y < image.height; ++y) {
    for (uint32_t x = 0; x < image.width; ++x) {
      const AtlasOwner owner = OwnerOfAtlasPoint(*layout, x + 0.5, y + 0.5);
      if (owner.base_face >= layout->base_faces()) continue;
      const AtlasPoint q = layout->Map(owner.base_face, owner.barycentric[0], owner.barycentric[1],
                                       owner.barycentric[2]);
      if (std::hypot(q.x - x - 0.5, q.y - y - 0.5) < 0.5) continue;  // not a gutter texel
      // The inside texel nearest to q, a little towards the triangle's centre.
      const auto t = layout->Triangle(owner.base_face);
      const double cx = (t[0].x + t[1].x + t[2].x) / 3, cy = (t[0].y + t[1].y + t[2].y) / 3;
      const double ix = q.x + 0.75 * (cx - q.x) / std::hypot(cx - q.x, cy - q.y);
      const double iy = q.y + 0.75 * (cy - q.y) / std::hypot(cx - q.x, cy - q.y);
      const uint8_t* g = &image.rgba[(size_t{y} * image.width + x) * 4];
      const uint8_t* in =
          &image.rgba[(static_cast<size_t>(iy) * image.width + static_cast<size_t>(ix)) * 4];
      for (int c = 0; c < 3; ++c)
        gutter_error += std::abs(static_cast<double>(g[c]) - static_cast<double>(in[c]));
      gutter_texels += 3;
    }
  }
  ASSERT_GT(gutter_texels, 0);
  EXPECT_LT(gutter_error / gutter_texels, 6.0);
}

// A square of 32 faces wearing the die's texture (with clamped UVs past
// its edge on one side): small, so each bake takes milliseconds.
MeshAsset TexturedSquare() {
  MeshAsset die = Die();
  MeshAsset asset;
  asset.mesh = testing::GridPatch(4, 0, 0, 1);
  asset.uv.faces = asset.mesh.faces;
  for (const Vec3& p : asset.mesh.positions) {
    asset.uv.values.emplace_back(static_cast<float>(1.2 * p[0]), static_cast<float>(p[1]));
  }
  asset.images = std::move(die.images);
  asset.materials = std::move(die.materials);
  asset.face_material.assign(asset.mesh.faces.size(), 0);
  return asset;
}

TEST(TextureBakeTest, MakesAPyramidOfHalvingSizesIndependentOfThreads) {
  const MeshAsset die = TexturedSquare();
  const SemiRegularMesh mesh = Refined(die.mesh, 1);
  TextureBakeOptions options;
  options.cell = 64;
  options.levels = 3;
  options.threads = 1;
  auto one = BakeTexture(die, mesh, options);
  options.threads = 3;
  auto three = BakeTexture(die, mesh, options);
  ASSERT_TRUE(one.ok()) << one.status().ToString();
  ASSERT_TRUE(three.ok()) << three.status().ToString();
  ASSERT_TRUE(one->has_value() && three->has_value());
  const BakedTexture& texture = **one;
  EXPECT_EQ(texture.atlas.cell, 64u);
  EXPECT_EQ(texture.atlas.gutter, 4u);  // one texel at the coarsest of 3 levels
  ASSERT_EQ(texture.maps.size(), (*three)->maps.size());
  for (size_t m = 0; m < texture.maps.size(); ++m) {
    ASSERT_EQ(texture.maps[m].levels.size(), 3u);
    EXPECT_EQ(texture.maps[m].levels, (*three)->maps[m].levels) << "map " << m;
    const DecodedImage full = Decode(texture.maps[m].levels[2]);
    for (int k = 0; k < 3; ++k) {
      const DecodedImage level = Decode(texture.maps[m].levels[static_cast<size_t>(k)]);
      EXPECT_EQ(level.width, full.width >> (2 - k));
      EXPECT_EQ(level.height, full.height >> (2 - k));
    }
  }
}

TEST(TextureBakeTest, BakesDifferingScalarsAndKeepsCommonOnes) {
  // ring.glb: a textured half (roughness 0.8) and a vertex-coloured half
  // (roughness 0.5), both metallic 0.
  auto ring = ReadMeshAsset(testing::SampleMesh("textured/ring.glb"));
  ASSERT_TRUE(ring.ok()) << ring.status().ToString();
  auto remesh = Subdivide(ring->mesh, 1, SubdivisionScheme::kMidpoint);
  ASSERT_TRUE(remesh.ok()) << remesh.status().ToString();
  TextureBakeOptions options;
  options.cell = 16;
  options.levels = 1;
  auto baked = BakeTexture(*ring, *remesh, options);
  ASSERT_TRUE(baked.ok()) << baked.status().ToString();
  ASSERT_TRUE(baked->has_value());
  const BakedTexture& texture = **baked;
  EXPECT_EQ(texture.material.roughness_factor, 1.0f);
  const TextureMap* orm = FindMap(texture, TextureRole::kMetallicRoughness);
  ASSERT_NE(orm, nullptr);
  EXPECT_EQ(FindMap(texture, TextureRole::kNormal), nullptr);
  EXPECT_EQ(FindMap(texture, TextureRole::kEmissive), nullptr);
  const DecodedImage image = Decode(orm->levels.back());
  auto layout = AtlasLayout::Create(static_cast<uint32_t>(remesh->hierarchy->faces(0).size()), 16,
                                    texture.atlas.gutter, texture.atlas.columns);
  ASSERT_TRUE(layout.ok());
  int rough = 0, smooth = 0, metallic = 0, owned = 0;
  for (size_t i = 0; i < image.rgba.size(); i += 4) {
    const size_t x = i / 4 % image.width, y = i / 4 / image.width;
    if (OwnerOfAtlasPoint(*layout, x + 0.5, y + 0.5).base_face >= layout->base_faces()) continue;
    ++owned;
    // JPEG rings where the roughness steps, into blue too (YCbCr mixes
    // the channels): metallic 0 but for a few texels.
    metallic += image.rgba[i + 2] > 12;
    rough += std::abs(image.rgba[i + 1] - 204) <= 6;
    smooth += std::abs(image.rgba[i + 1] - 128) <= 6;
  }
  EXPECT_LT(metallic, owned / 50);
  EXPECT_GT(rough, owned / 5);
  EXPECT_GT(smooth, owned / 5);
}

TEST(TextureBakeTest, CarriesNormalsIntoTheAtlasTangentFrame) {
  // A flat square with UVs along x and y and a constant normal map leaning
  // towards +u: the object-space normal (0.6, 0, 0.8) everywhere.
  MeshAsset asset;
  asset.mesh = testing::GridPatch(4, 0, 0, 1);
  asset.uv.faces = asset.mesh.faces;
  for (const Vec3& p : asset.mesh.positions) {
    asset.uv.values.emplace_back(static_cast<float>(p[0]), static_cast<float>(p[1]));
  }
  AssetImage map;
  map.width = 2;
  map.height = 2;
  const uint8_t leaning[4] = {204, 128, 230, 255};
  map.rgba.resize(16);
  for (size_t i = 0; i < map.rgba.size(); ++i) map.rgba[i] = leaning[i % 4];
  asset.images.push_back(map);
  Material material;
  material.normal_texture.image = 0;
  asset.materials.push_back(material);
  asset.face_material.assign(asset.mesh.faces.size(), 0);
  const Vec3 expected = Vec3(204 / 127.5 - 1, 128 / 127.5 - 1, 230 / 127.5 - 1).normalized();

  const SemiRegularMesh mesh = Refined(asset.mesh, 2);
  TextureBakeOptions options;
  options.cell = 32;
  options.levels = 1;
  auto baked = BakeTexture(asset, mesh, options);
  ASSERT_TRUE(baked.ok()) << baked.status().ToString();
  ASSERT_TRUE(baked->has_value());
  const TextureMap* normal = FindMap(**baked, TextureRole::kNormal);
  ASSERT_NE(normal, nullptr);
  EXPECT_EQ(normal->mime_type, "image/png");
  const DecodedImage image = Decode(normal->levels.back());
  auto layout = AtlasLayout::Create(static_cast<uint32_t>(mesh.hierarchy->faces(0).size()), 32,
                                    (*baked)->atlas.gutter, (*baked)->atlas.columns);
  ASSERT_TRUE(layout.ok());
  int checked = 0;
  for (uint32_t y = 0; y < image.height; y += 3) {
    for (uint32_t x = 0; x < image.width; x += 3) {
      const AtlasOwner owner = OwnerOfAtlasPoint(*layout, x + 0.5, y + 0.5);
      if (owner.base_face >= layout->base_faces()) continue;
      // The finest face's frame in atlas UVs, as a renderer builds it.
      const FinestPoint fine = DescendToFinest(2, owner.base_face, owner.barycentric);
      const BaseTriangle base = FinestFaceInBase(2, fine.face);
      const Face& f = mesh.hierarchy->faces(2)[fine.face];
      std::array<Vec3, 3> p;
      std::array<Eigen::Vector2d, 3> uv;
      for (int k = 0; k < 3; ++k) {
        p[k] = mesh.positions[f[k]];
        const AtlasPoint a =
            layout->Map(base.base_face, base.corners[k][0], base.corners[k][1], base.corners[k][2]);
        uv[k] = {a.x / layout->width(), a.y / layout->height()};
      }
      TangentFrame frame;
      ASSERT_TRUE(TriangleTangentFrame(p, uv, frame));
      const uint8_t* texel = &image.rgba[(size_t{y} * image.width + x) * 4];
      const Vec3 local(texel[0] / 127.5 - 1, texel[1] / 127.5 - 1, texel[2] / 127.5 - 1);
      const Vec3 object =
          (local[0] * frame.tangent + local[1] * frame.bitangent + local[2] * frame.normal)
              .normalized();
      EXPECT_LT((object - expected).norm(), 0.02) << "texel " << x << ", " << y;
      ++checked;
    }
  }
  EXPECT_GT(checked, 50);
}

TEST(TextureBakeTest, TakesTheSideOfAThinPartTheRemeshFaces) {
  // A thin sheet: a red top facing +z and, 0.02 below, a blue bottom facing
  // -z. The remesh runs just below the middle, nearer the bottom, facing
  // up: it stands for the top.
  MeshAsset asset;
  const TriMesh top = testing::GridPatch(4, 0, 0, 1);
  TriMesh bottom = testing::Translated(top, Vec3(0, 0, -0.02));
  for (Face& f : bottom.faces) std::swap(f[1], f[2]);
  asset.mesh = top;
  const auto offset = static_cast<uint32_t>(top.positions.size());
  asset.mesh.positions.insert(asset.mesh.positions.end(), bottom.positions.begin(),
                              bottom.positions.end());
  for (const Face& f : bottom.faces) {
    asset.mesh.faces.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
  }
  asset.materials.resize(2);
  asset.materials[0].base_color_factor = {1.0f, 0.0f, 0.0f, 1.0f};
  asset.materials[1].base_color_factor = {0.0f, 0.0f, 1.0f, 1.0f};
  asset.face_material.assign(top.faces.size(), 0);
  asset.face_material.resize(asset.mesh.faces.size(), 1);
  const SemiRegularMesh mesh =
      Refined(testing::Translated(testing::GridPatch(2, 0, 0, 1), Vec3(0, 0, -0.012)), 2);
  TextureBakeOptions options;
  options.cell = 16;
  options.levels = 1;
  auto baked = BakeTexture(asset, mesh, options);
  ASSERT_TRUE(baked.ok()) << baked.status().ToString();
  ASSERT_TRUE(baked->has_value());
  const DecodedImage image = Decode((*baked)->maps[0].levels.back());
  auto layout = AtlasLayout::Create(static_cast<uint32_t>(mesh.hierarchy->faces(0).size()), 16,
                                    (*baked)->atlas.gutter, (*baked)->atlas.columns);
  ASSERT_TRUE(layout.ok());
  int red = 0, owned = 0;
  for (uint32_t y = 0; y < image.height; ++y) {
    for (uint32_t x = 0; x < image.width; ++x) {
      if (OwnerOfAtlasPoint(*layout, x + 0.5, y + 0.5).base_face >= layout->base_faces()) continue;
      const uint8_t* p = &image.rgba[(size_t{y} * image.width + x) * 4];
      ++owned;
      red += p[0] > 200 && p[2] < 60;
    }
  }
  EXPECT_EQ(red, owned);
}

TEST(TextureBakeTest, GivesNothingForAnAssetWithoutTextures) {
  MeshAsset asset;
  asset.mesh = testing::GridPatch(2, 0, 0, 1);
  const SemiRegularMesh mesh = Refined(asset.mesh, 1);
  auto plain = BakeTexture(asset, mesh);
  ASSERT_TRUE(plain.ok()) << plain.status().ToString();
  EXPECT_FALSE(plain->has_value());

  // Vertex colours alone travel as a colour channel.
  auto ball = ReadMeshAsset(testing::SampleMesh("textured/hue_ball.ply"));
  ASSERT_TRUE(ball.ok()) << ball.status().ToString();
  auto ball_mesh = Subdivide(ball->mesh, 0, SubdivisionScheme::kMidpoint);
  ASSERT_TRUE(ball_mesh.ok()) << ball_mesh.status().ToString();
  auto colours = BakeTexture(*ball, *ball_mesh);
  ASSERT_TRUE(colours.ok()) << colours.status().ToString();
  EXPECT_FALSE(colours->has_value());

  // Two materials that differ do need maps, even without images.
  asset.materials.resize(2);
  asset.materials[1].base_color_factor = {1.0f, 0.0f, 0.0f, 1.0f};
  asset.face_material = {0, 0, 0, 0, 1, 1, 1, 1};
  auto differing = BakeTexture(asset, mesh);
  ASSERT_TRUE(differing.ok()) << differing.status().ToString();
  EXPECT_TRUE(differing->has_value());
}

}  // namespace
}  // namespace meshwave
