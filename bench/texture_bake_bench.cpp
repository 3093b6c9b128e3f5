// texture_bake_bench: the texture bake on real assets (docs/CODEC.md,
// "Texture baking"). For each asset: remesh it as `meshwave encode` does
// (ToSemiRegular at the default fidelity), bake its textures onto the
// remesh's atlas and report the bake's wall time, atlas and map sizes; the
// base colour's fidelity, as the PSNR (8-bit sRGB RGB) of the baked full
// level sampled bilinearly through the atlas at random points of the
// remesh's finest surface against the original's base colour at the
// nearest point of the original surface; and the alternative of coding UVs
// as a channel: the share of the finest faces whose corners' transferred
// UVs come from different UV charts (such a face would smear the texture
// across a seam).
//
//   texture_bake_bench ASSET... [--threads 2] [--points 100000] [--fidelity DB]
//                      [--max-side 4096] [--cell N] [--dump DIR]
//
// --fidelity is ToSemiRegular's (default: the encoder's, kDefaultFidelityDb;
// 0 remeshes once at the first density). --dump writes each map's full level to
// DIR/<asset>_<role>.<jpg|png>.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include "image/image_decoder.h"
#include "meshwave/mesh_asset.h"
#include "meshwave/mesh_io.h"
#include "meshwave/semiregular_input.h"
#include "meshwave/texture_bake.h"
#include "metrics/triangle_bvh.h"
#include "pipeline/color_transfer.h"
#include "pipeline/texel_correspondence.h"
#include "remesh/union_find.h"
#include "texture/atlas_layout.h"
#include "texture/material_sampler.h"
#include "texture/texture_density.h"

namespace {

using meshwave::Face;
using meshwave::Vec3;

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

// splitmix64: the same sequence everywhere.
class Random {
 public:
  explicit Random(uint64_t seed) : state_(seed) {}
  uint64_t Next() {
    uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  double Unit() { return static_cast<double>(Next() >> 11) * 0x1.0p-53; }

 private:
  uint64_t state_;
};

// Bilinear sample of a decoded 8-bit RGBA image at texel coordinates (x
// right, y down, texel centres at +0.5), clamped at the border.
Eigen::Vector3d SampleAtlas(const meshwave::DecodedImage& image, double x, double y) {
  const double fx = x - 0.5, fy = y - 0.5;
  const double x0 = std::floor(fx), y0 = std::floor(fy);
  const double tx = fx - x0, ty = fy - y0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int b = 0; b < 2; ++b) {
    for (int a = 0; a < 2; ++a) {
      const auto i = static_cast<uint32_t>(std::clamp(x0 + a, 0.0, image.width - 1.0));
      const auto j = static_cast<uint32_t>(std::clamp(y0 + b, 0.0, image.height - 1.0));
      const double w = (a ? tx : 1 - tx) * (b ? ty : 1 - ty);
      const uint8_t* p = &image.rgba[(size_t{j} * image.width + i) * 4];
      sum += w * Eigen::Vector3d(p[0], p[1], p[2]);
    }
  }
  return sum;
}

// sRGB encoding without rounding, in 0..255.
double LinearToSrgb255(double v) {
  v = std::clamp(v, 0.0, 1.0);
  return 255 * (v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055);
}

// UV charts: faces joined across an edge whose two ends have the same UVs
// on both sides.
std::vector<uint32_t> UvCharts(const meshwave::MeshAsset& asset, size_t& chart_count) {
  const auto& faces = asset.mesh.faces;
  meshwave::remesh::UnionFind charts(faces.size());
  std::map<std::pair<uint32_t, uint32_t>, std::vector<std::pair<uint32_t, int>>> edges;
  for (uint32_t f = 0; f < faces.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = faces[f][k], b = faces[f][(k + 1) % 3];
      edges[{std::min(a, b), std::max(a, b)}].emplace_back(f, k);
    }
  }
  auto uv_at = [&](uint32_t f, uint32_t vertex) {
    for (int k = 0; k < 3; ++k) {
      if (faces[f][k] == vertex) return asset.uv.values[asset.uv.faces[f][k]];
    }
    return Eigen::Vector2f(0, 0);
  };
  for (const auto& [edge, sides] : edges) {
    if (sides.size() != 2) continue;
    const uint32_t f = sides[0].first, g = sides[1].first;
    if ((uv_at(f, edge.first) - uv_at(g, edge.first)).norm() < 1e-6f &&
        (uv_at(f, edge.second) - uv_at(g, edge.second)).norm() < 1e-6f) {
      charts.Union(f, g);
    }
  }
  std::vector<uint32_t> chart(faces.size());
  std::map<uint32_t, uint32_t> ids;
  for (uint32_t f = 0; f < faces.size(); ++f) {
    const uint32_t root = charts.Find(f);
    chart[f] = ids.emplace(root, static_cast<uint32_t>(ids.size())).first->second;
  }
  chart_count = ids.size();
  return chart;
}

// TextureRoleName's definition comes with the stream format's texture
// support; the bench names the roles itself.
const char* RoleName(meshwave::TextureRole role) {
  switch (role) {
    case meshwave::TextureRole::kBaseColor:
      return "base colour";
    case meshwave::TextureRole::kMetallicRoughness:
      return "metallic-roughness";
    case meshwave::TextureRole::kNormal:
      return "normal";
    case meshwave::TextureRole::kOcclusion:
      return "occlusion";
    case meshwave::TextureRole::kEmissive:
      return "emissive";
  }
  return "?";
}

int Run(const std::string& path, int threads, int points, double fidelity_db, uint32_t max_side,
        uint32_t cell, const std::string& dump) {
  using namespace meshwave;
  auto asset = ReadMeshAsset(path);
  auto mesh = ReadMesh(path);
  if (!asset.ok() || !mesh.ok()) {
    std::fprintf(stderr, "%s: %s\n", path.c_str(),
                 (!asset.ok() ? asset.status() : mesh.status()).ToString().c_str());
    return 1;
  }
  SemiRegularInputOptions remesh_options;
  remesh_options.threads = threads;
  remesh_options.fidelity_db = fidelity_db;
  auto start = std::chrono::steady_clock::now();
  auto input = ToSemiRegular(std::move(*mesh), remesh_options);
  if (!input.ok()) {
    std::fprintf(stderr, "%s: %s\n", path.c_str(), input.status().ToString().c_str());
    return 1;
  }
  const double remesh_seconds = Seconds(start);
  const SemiRegularMesh& remesh = input->mesh;
  const int levels = remesh.levels();

  TextureBakeOptions options;
  options.threads = threads;
  options.max_side = max_side;
  options.cell = cell;
  TextureBakeNotes notes;
  start = std::chrono::steady_clock::now();
  auto baked = BakeTexture(*asset, remesh, options, &notes);
  const double bake_seconds = Seconds(start);
  if (!baked.ok() || !baked->has_value()) {
    std::fprintf(stderr, "%s: %s\n", path.c_str(),
                 baked.ok() ? "nothing to bake" : baked.status().ToString().c_str());
    return 1;
  }
  const BakedTexture& texture = **baked;
  const auto base_faces = static_cast<uint32_t>(remesh.hierarchy->faces(0).size());
  auto layout = AtlasLayout::Create(base_faces, texture.atlas.cell, texture.atlas.gutter,
                                    texture.atlas.columns);
  if (!layout.ok()) return 1;
  std::printf(
      "%s: %zu faces; remesh %.1f s (%d attempts, %.1f dB): %u base faces, %d levels, "
      "%zu finest faces\n",
      path.c_str(), asset->mesh.faces.size(), remesh_seconds, input->remesh_attempts,
      input->remesh_psnr_db, base_faces, levels, remesh.hierarchy->faces(levels).size());
  std::printf("  bake %.2f s (%d threads): atlas %u x %u, cell %u, gutter %u, %zu levels\n",
              bake_seconds, threads, layout->width(), layout->height(), texture.atlas.cell,
              texture.atlas.gutter, texture.maps[0].levels.size());
  const double gutter = texture.atlas.gutter;
  const double leg = texture.atlas.cell - 2 * gutter - std::ceil(std::sqrt(2.0) * gutter);
  std::printf("  texels: the original's textures spend %.0f, the atlas's triangles hold %.0f\n",
              TexelsOfOriginal(*asset), base_faces * 0.5 * leg * leg);
  for (const TextureMap& map : texture.maps) {
    size_t all = 0;
    for (const std::string& level : map.levels) all += level.size();
    std::printf("  %-20s %s: full %zu bytes, all levels %zu bytes\n", RoleName(map.role),
                map.mime_type.c_str(), map.levels.back().size(), all);
  }
  if (!dump.empty()) {
    for (const TextureMap& map : texture.maps) {
      std::string name = std::filesystem::path(path).stem().string() + "_" + RoleName(map.role) +
                         (map.mime_type == "image/png" ? ".png" : ".jpg");
      std::replace(name.begin(), name.end(), ' ', '_');
      std::ofstream(std::filesystem::path(dump) / name, std::ios::binary) << map.levels.back();
    }
  }
  for (const std::string& line : notes.lines) std::printf("  note: %s\n", line.c_str());

  // Fidelity of the base colour at random points of the finest surface.
  auto image = DecodeImage(texture.maps[0].levels.back(), {}, "base colour");
  if (!image.ok()) return 1;
  const TriMesh finest = remesh.Finest();
  std::vector<double> cumulative(finest.faces.size());
  double area = 0;
  for (size_t f = 0; f < finest.faces.size(); ++f) {
    const Face& c = finest.faces[f];
    area += 0.5 * (finest.positions[c[1]] - finest.positions[c[0]])
                      .cross(finest.positions[c[2]] - finest.positions[c[0]])
                      .norm();
    cumulative[f] = area;
  }
  const metrics::TriangleBvh bvh(asset->mesh.positions, asset->mesh.faces, threads);
  const MaterialSampler sampler(*asset);
  Random random(1);
  double squared = 0;
  for (int i = 0; i < points; ++i) {
    const auto f = static_cast<uint32_t>(
        std::lower_bound(cumulative.begin(), cumulative.end(), random.Unit() * area) -
        cumulative.begin());
    const uint32_t face = std::min<uint32_t>(f, static_cast<uint32_t>(finest.faces.size() - 1));
    double r1 = random.Unit(), r2 = random.Unit();
    if (r1 + r2 > 1) {
      r1 = 1 - r1;
      r2 = 1 - r2;
    }
    const Vec3 c(1 - r1 - r2, r1, r2);
    const Face& corners = finest.faces[face];
    const Vec3 p = c[0] * finest.positions[corners[0]] + c[1] * finest.positions[corners[1]] +
                   c[2] * finest.positions[corners[2]];
    const BaseTriangle base = FinestFaceInBase(levels, face);
    const Vec3 b = c[0] * base.corners[0] + c[1] * base.corners[1] + c[2] * base.corners[2];
    const AtlasPoint a = layout->Map(base.base_face, b[0], b[1], b[2]);
    const Eigen::Vector3d got = SampleAtlas(*image, a.x, a.y);
    const metrics::TriangleBvh::Hit hit = bvh.ClosestPoint(p);
    const Face& o = asset->mesh.faces[hit.face];
    const Vec3 w = ClosestBarycentric(hit.point, asset->mesh.positions[o[0]],
                                      asset->mesh.positions[o[1]], asset->mesh.positions[o[2]]);
    const Eigen::Vector4f want = sampler.BaseColor(hit.face, w);
    for (int k = 0; k < 3; ++k) {
      const double d = got[k] - LinearToSrgb255(want[k]);
      squared += d * d;
    }
  }
  const double mse = squared / (3.0 * points);
  std::printf("  base colour PSNR %.2f dB at %d points (RMS %.2f of 255)\n",
              10 * std::log10(255.0 * 255.0 / mse), points, std::sqrt(mse));

  // The alternative: UVs as a channel, each finest vertex taking the UV of
  // its nearest original point.
  if (!asset->uv.empty()) {
    size_t chart_count = 0;
    const std::vector<uint32_t> chart = UvCharts(*asset, chart_count);
    std::vector<uint32_t> vertex_chart(finest.positions.size());
    for (size_t v = 0; v < finest.positions.size(); ++v) {
      vertex_chart[v] = chart[bvh.ClosestPoint(finest.positions[v]).face];
    }
    size_t smeared = 0;
    for (const Face& f : finest.faces) {
      smeared +=
          vertex_chart[f[0]] != vertex_chart[f[1]] || vertex_chart[f[1]] != vertex_chart[f[2]];
    }
    std::printf("  UVs as a channel: %zu charts; %zu of %zu finest faces (%.2f%%) span charts\n",
                chart_count, smeared, finest.faces.size(),
                100.0 * static_cast<double>(smeared) / static_cast<double>(finest.faces.size()));
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // each asset's lines as they come
  int threads = 2, points = 100000;
  double fidelity_db = meshwave::kDefaultFidelityDb;
  uint32_t max_side = 4096;
  uint32_t cell = 0;
  std::string dump;
  std::vector<std::string> paths;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--threads" && i + 1 < argc) {
      threads = std::atoi(argv[++i]);
    } else if (arg == "--points" && i + 1 < argc) {
      points = std::max(1, std::atoi(argv[++i]));
    } else if (arg == "--fidelity" && i + 1 < argc) {
      fidelity_db = std::atof(argv[++i]);
    } else if (arg == "--max-side" && i + 1 < argc) {
      max_side = static_cast<uint32_t>(std::atoi(argv[++i]));
    } else if (arg == "--cell" && i + 1 < argc) {
      cell = static_cast<uint32_t>(std::atoi(argv[++i]));
    } else if (arg == "--dump" && i + 1 < argc) {
      dump = argv[++i];
    } else {
      paths.push_back(arg);
    }
  }
  if (paths.empty()) {
    std::fprintf(stderr,
                 "usage: texture_bake_bench ASSET... [--threads 2] [--points 100000] "
                 "[--fidelity DB] [--max-side 4096] [--cell N] [--dump DIR]\n");
    return 2;
  }
  int status = 0;
  for (const std::string& path : paths)
    status |= Run(path, threads, points, fidelity_db, max_side, cell, dump);
  return status;
}
