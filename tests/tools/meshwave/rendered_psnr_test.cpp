// The image measure of `meshwave render-compare`: cameras, one framing for
// both meshes, luma PSNR over the pixels either covers.
#include "rendered_psnr.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

namespace meshwave::cli {
namespace {

// A closed tetrahedron coloured uniformly by its material: every camera
// sees it, and without light each covered pixel is that colour.
MeshAsset Tetrahedron(float grey, double scale = 1) {
  MeshAsset a;
  a.mesh.positions = {scale * Vec3(1, 1, 1), scale * Vec3(-1, -1, 1), scale * Vec3(-1, 1, -1),
                      scale * Vec3(1, -1, -1)};
  a.mesh.faces = {Face{0, 1, 2}, Face{0, 3, 1}, Face{0, 2, 3}, Face{1, 3, 2}};
  Material m;
  m.base_color_factor = Eigen::Vector4f(grey, grey, grey, 1);
  a.materials.push_back(m);
  a.face_material.assign(4, 0);
  return a;
}

const RenderedPsnrOptions kOneSample{16, 96, 1, false};

TEST(RenderedPsnrTest, ViewsCircleTheObjectAboveAndBelow) {
  const std::vector<View> views = MetricViews(16, 64);
  ASSERT_EQ(views.size(), 16u);
  std::set<double> azimuths;
  int above = 0;
  for (const View& v : views) {
    EXPECT_EQ(v.width, 64);
    EXPECT_EQ(std::fabs(v.elevation_deg), 25);
    above += v.elevation_deg > 0;
    azimuths.insert(v.azimuth_deg);
  }
  EXPECT_EQ(above, 8);
  EXPECT_EQ(azimuths.size(), 16u);  // below interleaves with above
}

TEST(RenderedPsnrTest, TheSameMeshIsInfinitelyClose) {
  std::vector<View> views = MetricViews(4, 96);
  const Pictures a = RenderReference(Tetrahedron(0.5f), views, kOneSample);
  const LumaPsnr psnr = CompareLuma(a, RenderLike(Tetrahedron(0.5f), views, kOneSample));
  EXPECT_TRUE(std::isinf(psnr.db));
  EXPECT_GT(psnr.object_pixels, 4u * 96 * 96 / 4);
}

TEST(RenderedPsnrTest, AUniformLumaErrorGivesItsPsnr) {
  // Without light a base colour comes back to its own sRGB byte, so two
  // greys 10 apart on every pixel are 20 log10(255 / 10) dB apart.
  std::vector<View> views = MetricViews(4, 96);
  const float linear100 = std::pow((100 / 255.0f + 0.055f) / 1.055f, 2.4f);
  const float linear110 = std::pow((110 / 255.0f + 0.055f) / 1.055f, 2.4f);
  const Pictures a = RenderReference(Tetrahedron(linear100), views, kOneSample);
  const LumaPsnr psnr = CompareLuma(a, RenderLike(Tetrahedron(linear110), views, kOneSample));
  EXPECT_NEAR(psnr.db, 20 * std::log10(255.0 / 10), 0.05);
}

TEST(RenderedPsnrTest, TheOtherMeshIsFramedAsTheReference) {
  // A copy at half the size stays half the size on screen (its own box
  // would blow it up to fill the picture), so the reference's pixels it
  // leaves bare count against it, at white's distance from the grey.
  std::vector<View> views = MetricViews(2, 96);
  const Pictures a = RenderReference(Tetrahedron(0.2f), views, kOneSample);
  const Pictures half = RenderLike(Tetrahedron(0.2f, 0.5), views, kOneSample);
  size_t covered_a = 0, covered_half = 0;
  for (size_t v = 0; v < views.size(); ++v) {
    for (size_t i = 0; i < a.covered[v].size(); ++i) {
      covered_a += a.covered[v][i];
      covered_half += half.covered[v][i];
    }
  }
  EXPECT_NEAR(static_cast<double>(covered_half) / static_cast<double>(covered_a), 0.25, 0.03);
  const LumaPsnr psnr = CompareLuma(a, half);
  EXPECT_EQ(psnr.object_pixels, covered_a);  // the half copy lies inside the reference
  EXPECT_LT(psnr.db, 10);
}

TEST(RenderedPsnrTest, SupersamplingAveragesEdgesAndKeepsFlatColour) {
  // Inside the tetrahedron every sample is the same grey, so the supersampled
  // picture keeps it; on its edges pixels take partial coverage, so the
  // picture holds greys between the object's and the white background.
  std::vector<View> views = MetricViews(1, 64);
  RenderedPsnrOptions options{1, 64, 4, false};
  const Pictures p = RenderReference(Tetrahedron(0.2f), views, options);
  const Pictures one = RenderLike(Tetrahedron(0.2f), views, kOneSample);
  const uint8_t inside = one.rgb[0][3 * (32 * 64 + 32)];
  EXPECT_EQ(p.rgb[0][3 * (32 * 64 + 32)], inside);
  int between = 0;
  for (size_t i = 0; i < p.covered[0].size(); ++i) {
    const uint8_t v = p.rgb[0][3 * i];
    between += p.covered[0][i] && v > inside + 2 && v < 253;
  }
  EXPECT_GT(between, 20);
  // Each picture is still compared with itself exactly.
  EXPECT_TRUE(std::isinf(CompareLuma(p, RenderLike(Tetrahedron(0.2f), views, options)).db));
}

}  // namespace
}  // namespace meshwave::cli
