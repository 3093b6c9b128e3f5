#include "rendered_psnr.h"

#include <cmath>
#include <limits>

#include "appearance_shader.h"

namespace meshwave::cli {
namespace {

PixelShader ShaderFor(const MeshAsset& asset, bool lit) {
  if (HasAppearance(asset)) return AppearanceShader(asset, lit);
  // Geometry alone: one grey, as `render` draws it.
  return [lit](uint32_t, const Vec3& weights, const Vec3& light) -> std::optional<Rgb8> {
    const double level = 0.7 * (lit ? weights.dot(light) : 1.0);
    const auto v = static_cast<uint8_t>(std::lround(255 * std::pow(level, 1 / 2.2)));
    return Rgb8{v, v, v};
  };
}

double Luma(const uint8_t* rgb) {
  return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
}

}  // namespace

std::vector<View> MetricViews(int count, int size) {
  std::vector<View> views;
  const int upper = (count + 1) / 2, lower = count - upper;
  for (int k = 0; k < upper; ++k) {
    views.push_back(View{360.0 * k / upper, 25, size, size, std::nullopt});
  }
  for (int k = 0; k < lower; ++k) {
    views.push_back(View{360.0 * (k + 0.5) / lower, -25, size, size, std::nullopt});
  }
  return views;
}

Pictures RenderReference(const MeshAsset& reference, std::vector<View>& views, bool lit) {
  for (View& v : views) v.framing = FitFraming(reference.mesh, v);
  return RenderLike(reference, views, lit);
}

Pictures RenderLike(const MeshAsset& asset, const std::vector<View>& views, bool lit) {
  const PixelShader shade = ShaderFor(asset, lit);
  Pictures p;
  for (const View& v : views) {
    p.covered.emplace_back();
    p.rgb.push_back(Rasterize(asset.mesh, shade, v, &p.covered.back()));
  }
  return p;
}

LumaPsnr CompareLuma(const Pictures& reference, const Pictures& other) {
  double sum = 0;
  LumaPsnr out;
  for (size_t v = 0; v < reference.rgb.size() && v < other.rgb.size(); ++v) {
    const std::vector<uint8_t>& a = reference.rgb[v];
    const std::vector<uint8_t>& b = other.rgb[v];
    for (size_t i = 0; i < reference.covered[v].size(); ++i) {
      if (!reference.covered[v][i] && !other.covered[v][i]) continue;
      ++out.object_pixels;
      const double d = Luma(&a[3 * i]) - Luma(&b[3 * i]);
      sum += d * d;
    }
  }
  if (out.object_pixels == 0 || sum == 0) {
    out.db = std::numeric_limits<double>::infinity();
  } else {
    out.db = 10 * std::log10(255.0 * 255.0 * static_cast<double>(out.object_pixels) / sum);
  }
  return out;
}

}  // namespace meshwave::cli
