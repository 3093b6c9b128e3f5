// The rasterizer of `meshwave render` with the appearance shader: where a
// texture lands on screen (glTF's UV convention), what is grey and what
// is not, see-through masked texels.
#include "rasterizer.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <vector>

#include "appearance_shader.h"
#include "meshwave/mesh_asset.h"

namespace meshwave::cli {
namespace {

using Rgba = std::array<uint8_t, 4>;

// A unit square facing the viewer (x right, y up), textured by a 2x2
// image whose rows are given top to bottom. The corners' UVs follow glTF:
// (0, 0) at the image's top-left, v growing downwards, so the image's top
// row belongs on the square's top edge (y = 1).
MeshAsset TexturedSquare(const std::array<Rgba, 4>& texels) {
  MeshAsset a;
  a.mesh.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
  a.mesh.faces = {Face{0, 1, 2}, Face{0, 2, 3}};
  a.uv.values = {Eigen::Vector2f(0, 1), Eigen::Vector2f(1, 1), Eigen::Vector2f(1, 0),
                 Eigen::Vector2f(0, 0)};
  a.uv.faces = a.mesh.faces;
  AssetImage image;
  image.width = image.height = 2;
  for (const Rgba& t : texels) image.rgba.insert(image.rgba.end(), t.begin(), t.end());
  a.images.push_back(image);
  Material m;
  m.base_color_texture.image = 0;
  m.base_color_texture.wrap_u = m.base_color_texture.wrap_v = WrapMode::kClampToEdge;
  a.materials.push_back(m);
  a.face_material = {0, 0};
  return a;
}

constexpr int kSide = 64;

std::vector<uint8_t> Render(const MeshAsset& asset) {
  return Rasterize(asset.mesh, AppearanceShader(asset), View{0, 0, kSide, kSide, std::nullopt});
}

// The pixel at (x, y), rows top to bottom.
Rgb8 At(const std::vector<uint8_t>& rgb, int x, int y) {
  const size_t i = (static_cast<size_t>(y) * kSide + static_cast<size_t>(x)) * 3;
  return {rgb[i], rgb[i + 1], rgb[i + 2]};
}

bool Reddish(const Rgb8& p) { return p[0] > 180 && p[1] < 60 && p[2] < 60; }
bool Bluish(const Rgb8& p) { return p[2] > 180 && p[0] < 60 && p[1] < 60; }

constexpr Rgba kRed{255, 0, 0, 255}, kBlue{0, 0, 255, 255};

TEST(RasterizerTest, TheImagesTopRowLandsOnTheTopOfTheSquare) {
  const std::vector<uint8_t> rgb = Render(TexturedSquare({kRed, kRed, kBlue, kBlue}));
  // Quarter and three-quarter heights, away from the blend at the middle.
  for (int x : {16, 32, 48}) {
    EXPECT_TRUE(Reddish(At(rgb, x, 16))) << x;
    EXPECT_TRUE(Bluish(At(rgb, x, 48))) << x;
  }
}

TEST(RasterizerTest, TheImagesLeftColumnLandsOnTheLeftOfTheSquare) {
  const std::vector<uint8_t> rgb = Render(TexturedSquare({kRed, kBlue, kRed, kBlue}));
  for (int y : {16, 32, 48}) {
    EXPECT_TRUE(Reddish(At(rgb, 16, y))) << y;
    EXPECT_TRUE(Bluish(At(rgb, 48, y))) << y;
  }
}

TEST(RasterizerTest, ShadesInLinearLight) {
  // The square faces the viewer; the light comes from (0.3, 0.4, 1), so
  // the square's light is 0.25 + 0.75 * 0.894. Shading happens in linear
  // light: mid-grey 128 comes back as sRGB(0.92 * linear(128)) = 123, not
  // the 118 that scaling the sRGB byte would give.
  const Rgba grey{128, 128, 128, 255};
  const std::vector<uint8_t> rgb = Render(TexturedSquare({grey, grey, grey, grey}));
  const Rgb8 p = At(rgb, 32, 32);
  EXPECT_EQ(p[0], p[1]);
  EXPECT_EQ(p[1], p[2]);
  EXPECT_NEAR(p[0], 123, 1);
}

TEST(RasterizerTest, MaskedTexelsAreSeeThrough) {
  MeshAsset a = TexturedSquare({kRed, kRed, Rgba{0, 0, 255, 0}, Rgba{0, 0, 255, 0}});
  a.materials[0].alpha_mode = AlphaMode::kMask;
  const std::vector<uint8_t> rgb = Render(a);
  EXPECT_TRUE(Reddish(At(rgb, 32, 16)));
  EXPECT_EQ(At(rgb, 32, 48), (Rgb8{255, 255, 255}));  // the background
}

TEST(RasterizerTest, OnlyAttributesThatChangeTheLookCount) {
  MeshAsset a = TexturedSquare({kRed, kRed, kBlue, kBlue});
  EXPECT_TRUE(HasAppearance(a));
  a.materials[0].base_color_texture.image = -1;  // UVs alone: nothing to draw
  EXPECT_FALSE(HasAppearance(a));
  a.materials[0].base_color_factor = Eigen::Vector4f(1, 0.5f, 0.5f, 1);
  EXPECT_TRUE(HasAppearance(a));
  a.materials[0].base_color_factor = Eigen::Vector4f::Ones();
  a.color.values = {Eigen::Vector4f(0, 1, 0, 1)};
  a.color.faces = {Face{0, 0, 0}, Face{0, 0, 0}};
  EXPECT_TRUE(HasAppearance(a));
}

TEST(RasterizerTest, VertexColoursAreInterpolatedAcrossFaces) {
  MeshAsset a = TexturedSquare({kRed, kRed, kRed, kRed});
  a.materials[0].base_color_texture.image = -1;
  // Left corners red, right corners blue (linear RGBA).
  a.color.values = {Eigen::Vector4f(1, 0, 0, 1), Eigen::Vector4f(0, 0, 1, 1)};
  a.color.faces = {Face{0, 1, 1}, Face{0, 1, 0}};
  const std::vector<uint8_t> rgb = Render(a);
  const Rgb8 left = At(rgb, 3, 32), middle = At(rgb, 32, 32), right = At(rgb, 60, 32);
  EXPECT_TRUE(Reddish(left));
  EXPECT_TRUE(Bluish(right));
  EXPECT_GT(middle[0], 100);  // a mix of both
  EXPECT_GT(middle[2], 100);
}

}  // namespace
}  // namespace meshwave::cli
