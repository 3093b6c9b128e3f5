#include "rendered_psnr.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>

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

// One view drawn at `s` samples a side per pixel, then box-filtered.
void RenderView(const MeshAsset& asset, const PixelShader& shade, View view, int s,
                std::vector<uint8_t>& rgb, std::vector<uint8_t>& covered) {
  const int w = view.width, h = view.height;
  view.width *= s;
  view.height *= s;
  if (view.framing) view.framing->pixels_per_unit *= s;
  std::vector<uint8_t> samples_covered;
  const std::vector<uint8_t> samples = Rasterize(asset.mesh, shade, view, &samples_covered);
  rgb.assign(size_t(w) * size_t(h) * 3, 0);
  covered.assign(size_t(w) * size_t(h), 0);
  const size_t sw = size_t(view.width);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      unsigned sum[3] = {0, 0, 0};
      uint8_t any = 0;
      for (int dy = 0; dy < s; ++dy) {
        for (int dx = 0; dx < s; ++dx) {
          const size_t at = size_t(y * s + dy) * sw + size_t(x * s + dx);
          any |= samples_covered[at];
          for (int c = 0; c < 3; ++c) sum[c] += samples[3 * at + size_t(c)];
        }
      }
      const size_t at = size_t(y) * size_t(w) + size_t(x);
      covered[at] = any;
      const unsigned n = unsigned(s * s);
      for (int c = 0; c < 3; ++c) rgb[3 * at + size_t(c)] = uint8_t((sum[c] + n / 2) / n);
    }
  }
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

Pictures RenderReference(const MeshAsset& reference, std::vector<View>& views,
                         const RenderedPsnrOptions& options) {
  for (View& v : views) v.framing = FitFraming(reference.mesh, v);
  return RenderLike(reference, views, options);
}

Pictures RenderLike(const MeshAsset& asset, const std::vector<View>& views,
                    const RenderedPsnrOptions& options) {
  const PixelShader shade = ShaderFor(asset, options.lit);
  Pictures p;
  p.rgb.resize(views.size());
  p.covered.resize(views.size());
  // The views on two threads: each writes its own pictures.
  const size_t workers = std::min<size_t>(2, views.size());
  std::vector<std::thread> threads;
  for (size_t t = 0; t < workers; ++t) {
    threads.emplace_back([&, t] {
      for (size_t v = t; v < views.size(); v += workers) {
        RenderView(asset, shade, views[v], std::max(1, options.supersample), p.rgb[v],
                   p.covered[v]);
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
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
