// BakeTexture: plans the atlas and the maps, fills every texel from the
// original's material at its corresponding point (texel_correspondence.h,
// material_sampler.h), filters the pyramid (texture_pyramid.h) and encodes
// each level. The method is that of re-baking a texture onto a new
// parameterisation (Sander, Snyder, Gortler, Hoppe, "Texture mapping
// progressive meshes", 2001) with the base domain of a semi-regular mesh as
// the parameter domain, as geometry images use a fixed domain (Gu, Gortler,
// Hoppe, "Geometry images", 2002).
#include "meshwave/texture_bake.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <optional>
#include <set>
#include <string>

#include "core/parallel_for.h"
#include "image/image_encoder.h"
#include "pipeline/texel_correspondence.h"
#include "texture/atlas_layout.h"
#include "texture/material_sampler.h"
#include "texture/texture_density.h"
#include "texture/texture_pyramid.h"

namespace meshwave {
namespace {

// Auto sizing: the smallest cell of the coarsest level. A cell of 8 texels
// with its one-texel gutter leaves 32% of the atlas to the triangles, one
// of 16 leaves 62%: the gutter is 2^(levels - 1) texels at full size, so
// the coarsest cell fixes the share at every level.
constexpr uint32_t kMinCoarsestCell = 16;
constexpr uint32_t kMaxCoarsestSide = 64;  // small atlases still arrive in two steps

Status CheckAsset(const MeshAsset& asset) {
  const size_t faces = asset.mesh.faces.size();
  if (faces == 0) return InvalidArgument("texture bake: the asset has no faces");
  for (const Face& f : asset.mesh.faces) {
    for (uint32_t v : f) {
      if (v >= asset.mesh.positions.size()) {
        return InvalidArgument("texture bake: a face indexes past the asset's positions");
      }
    }
  }
  auto check_corners = [&](const auto& attribute, const char* what) -> Status {
    if (attribute.empty()) return Status::Ok();
    if (attribute.faces.size() != faces) {
      return InvalidArgument(std::string("texture bake: ") +
                             std::to_string(attribute.faces.size()) + " " + what +
                             " corner triples for " + std::to_string(faces) + " faces");
    }
    for (const Face& f : attribute.faces) {
      for (uint32_t v : f) {
        if (v >= attribute.values.size()) {
          return InvalidArgument(std::string("texture bake: a face indexes past the ") + what +
                                 " values");
        }
      }
    }
    return Status::Ok();
  };
  MW_RETURN_IF_ERROR(check_corners(asset.uv, "UV"));
  MW_RETURN_IF_ERROR(check_corners(asset.color, "colour"));
  if (!asset.face_material.empty() && asset.face_material.size() != faces) {
    return InvalidArgument("texture bake: " + std::to_string(asset.face_material.size()) +
                           " face materials for " + std::to_string(faces) + " faces");
  }
  for (const Vec3& p : asset.mesh.positions) {
    if (!p.allFinite()) return InvalidArgument("texture bake: a position is not finite");
  }
  return Status::Ok();
}

bool HasImage(const MeshAsset& asset, const TextureRef& ref) {
  return ref.present() && static_cast<size_t>(ref.image) < asset.images.size() &&
         !asset.images[static_cast<size_t>(ref.image)].rgba.empty();
}

// What is baked, from the materials the faces use.
struct BakePlan {
  std::vector<const Material*> materials;  // used, in order of first use
  bool any_texture = false;
  bool alike = true;
  bool metallic_roughness = false;
  bool occlusion = false;  // in R of the metallic-roughness map
  bool emissive = false;
  bool normal = false;
  float emissive_scale = 1;  // baked emissive = value / scale
};

bool SameScalars(const Material& a, const Material& b) {
  return a.base_color_factor == b.base_color_factor && a.metallic_factor == b.metallic_factor &&
         a.roughness_factor == b.roughness_factor && a.emissive_factor == b.emissive_factor &&
         a.normal_scale == b.normal_scale && a.occlusion_strength == b.occlusion_strength &&
         a.alpha_mode == b.alpha_mode && a.alpha_cutoff == b.alpha_cutoff &&
         a.double_sided == b.double_sided;
}

BakePlan PlanBake(const MeshAsset& asset, const MaterialSampler& sampler) {
  BakePlan plan;
  std::set<const Material*> seen;
  for (uint32_t f = 0; f < asset.mesh.faces.size(); ++f) {
    const Material* m = &sampler.MaterialOf(f);
    if (seen.insert(m).second) plan.materials.push_back(m);
  }
  const Material& first = *plan.materials.front();
  for (const Material* m : plan.materials) {
    const bool base = HasImage(asset, m->base_color_texture);
    const bool mr = HasImage(asset, m->metallic_roughness_texture);
    const bool occlusion = HasImage(asset, m->occlusion_texture);
    const bool emissive = HasImage(asset, m->emissive_texture);
    const bool normal = HasImage(asset, m->normal_texture);
    plan.any_texture = plan.any_texture || base || mr || occlusion || emissive || normal;
    plan.alike = plan.alike && SameScalars(*m, first);
    plan.metallic_roughness = plan.metallic_roughness || mr || occlusion ||
                              m->metallic_factor != first.metallic_factor ||
                              m->roughness_factor != first.roughness_factor;
    plan.occlusion = plan.occlusion || occlusion;
    plan.emissive = plan.emissive || emissive || m->emissive_factor != first.emissive_factor;
    plan.normal = plan.normal || normal;
    plan.emissive_scale = std::max(plan.emissive_scale, m->emissive_factor.maxCoeff());
  }
  return plan;
}

struct AtlasPlan {
  uint32_t cell = 0;
  uint32_t gutter = 0;
  int levels = 1;
};

int AutoLevels(uint32_t cell, uint64_t side) {
  int levels = 1;
  while ((side >> (levels - 1)) > kMaxCoarsestSide && (cell >> levels) >= kMinCoarsestCell) {
    ++levels;
  }
  return levels;
}

uint64_t AtlasSide(uint32_t base_faces, uint32_t cell) {
  const uint64_t cells = (uint64_t{base_faces} + 1) / 2;
  const auto columns = static_cast<uint64_t>(std::ceil(std::sqrt(static_cast<double>(cells))));
  const uint64_t rows = (cells + columns - 1) / columns;
  return std::max(columns, rows) * cell;
}

Result<AtlasPlan> PlanAtlas(uint32_t base_faces, double texels_wanted,
                            const TextureBakeOptions& options) {
  auto complete = [&](uint32_t cell) -> std::optional<AtlasPlan> {
    AtlasPlan plan;
    plan.cell = cell;
    plan.levels =
        options.levels > 0 ? options.levels : AutoLevels(cell, AtlasSide(base_faces, cell));
    plan.gutter =
        options.gutter >= 0 ? static_cast<uint32_t>(options.gutter) : (1u << (plan.levels - 1));
    if (cell < 4 * uint64_t{plan.gutter} + 8) return std::nullopt;
    return plan;
  };
  if (options.cell != 0) {
    if (options.levels > 0 && (options.levels > 12 || (options.cell >> (options.levels - 1)) < 4)) {
      return InvalidArgument("texture bake: " + std::to_string(options.levels) +
                             " pyramid levels leave cells of " + std::to_string(options.cell) +
                             " texels under 4 at the coarsest");
    }
    const std::optional<AtlasPlan> plan = complete(options.cell);
    if (!plan) {
      return InvalidArgument("texture bake: cells of " + std::to_string(options.cell) +
                             " texels cannot hold the gutter");
    }
    return *plan;
  }
  if (options.levels > 12) {
    return InvalidArgument("texture bake: " + std::to_string(options.levels) +
                           " pyramid levels (at most 12)");
  }
  std::optional<AtlasPlan> chosen;
  for (uint32_t cell = 16; cell <= 4096; cell *= 2) {
    if (AtlasSide(base_faces, cell) > options.max_side) break;
    if (options.levels > 0 && (cell >> (options.levels - 1)) < 4) continue;
    const std::optional<AtlasPlan> plan = complete(cell);
    if (!plan) continue;
    chosen = plan;
    const double leg = cell - 2.0 * plan->gutter - std::ceil(std::sqrt(2.0) * plan->gutter);
    const double texels = base_faces * 0.5 * leg * leg;
    // The nearest power of two: stop once within a factor sqrt(2) below.
    if (texels * std::sqrt(2.0) >= texels_wanted) break;
  }
  if (!chosen) {
    return InvalidArgument("texture bake: " + std::to_string(base_faces) +
                           " base faces do not fit an atlas of " +
                           std::to_string(options.max_side) + " texels a side");
  }
  return *chosen;
}

uint8_t UnitToByte(double v) {
  return static_cast<uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255));
}

// The full-size maps.
struct Maps {
  BakedImage base_color;  // RGBA
  BakedImage orm;         // RGB
  BakedImage emissive;    // RGB
  BakedImage normal;      // RGB
};

BakedImage Blank(uint32_t width, uint32_t height, int channels,
                 std::initializer_list<uint8_t> fill) {
  BakedImage image;
  image.width = width;
  image.height = height;
  image.channels = channels;
  image.pixels.resize(size_t{width} * height * static_cast<size_t>(channels));
  const std::vector<uint8_t> value(fill);
  for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = value[i % value.size()];
  return image;
}

// The tangent frame of a finest remesh face in atlas UVs.
TangentFrame RemeshFrame(const SemiRegularMesh& remesh, const AtlasLayout& layout,
                         uint32_t finest_face, bool& usable) {
  const int levels = remesh.levels();
  const BaseTriangle base = FinestFaceInBase(levels, finest_face);
  const Face& f = remesh.hierarchy->faces(levels)[finest_face];
  std::array<Vec3, 3> p;
  std::array<Eigen::Vector2d, 3> uv;
  for (int k = 0; k < 3; ++k) {
    p[k] = remesh.positions[f[k]];
    const Vec3& b = base.corners[k];
    const AtlasPoint a = layout.Map(base.base_face, b[0], b[1], b[2]);
    uv[k] = {a.x / layout.width(), a.y / layout.height()};
  }
  TangentFrame frame;
  usable = TriangleTangentFrame(p, uv, frame);
  return frame;
}

Maps BakeMaps(const MeshAsset& asset, const SemiRegularMesh& remesh, const AtlasLayout& layout,
              const BakePlan& plan, const MaterialSampler& sampler, int threads) {
  const uint32_t width = layout.width(), height = layout.height(), cell = layout.cell();
  Maps maps;
  maps.base_color = Blank(width, height, 4, {255, 255, 255, 255});
  if (plan.metallic_roughness) maps.orm = Blank(width, height, 3, {255, 255, 255});
  if (plan.emissive) maps.emissive = Blank(width, height, 3, {0, 0, 0});
  if (plan.normal) maps.normal = Blank(width, height, 3, {128, 128, 255});
  const TexelCorrespondence correspondence(layout, remesh, asset.mesh.positions, asset.mesh.faces,
                                           threads);
  const uint32_t used_cells = (layout.base_faces() + 1) / 2;
  ParallelFor(
      used_cells, threads,
      [&](size_t first, size_t last) {
        std::vector<TexelSource> sources;
        for (size_t k = first; k < last; ++k) {
          correspondence.Cell(static_cast<uint32_t>(k), sources);
          const uint32_t x0 = static_cast<uint32_t>(k % layout.columns()) * cell;
          const uint32_t y0 = static_cast<uint32_t>(k / layout.columns()) * cell;
          uint32_t frame_face = TexelSource::kNone;
          TangentFrame frame;
          bool frame_usable = false;
          for (uint32_t j = 0; j < cell; ++j) {
            for (uint32_t i = 0; i < cell; ++i) {
              const TexelSource& s = sources[size_t{j} * cell + i];
              if (s.original_face == TexelSource::kNone) continue;
              const size_t texel = size_t{y0 + j} * width + (x0 + i);
              const Vec3 w(1.0 - s.w1 - s.w2, s.w1, s.w2);
              const Eigen::Vector4f base = sampler.BaseColor(s.original_face, w);
              uint8_t* out = &maps.base_color.pixels[4 * texel];
              for (int c = 0; c < 3; ++c) out[c] = LinearToSrgbByte(base[c]);
              out[3] = UnitToByte(base[3]);
              if (plan.metallic_roughness) {
                const Eigen::Vector3f orm = sampler.OcclusionRoughnessMetallic(s.original_face, w);
                for (int c = 0; c < 3; ++c) maps.orm.pixels[3 * texel + c] = UnitToByte(orm[c]);
                if (!plan.occlusion) maps.orm.pixels[3 * texel] = 255;
              }
              if (plan.emissive) {
                const Eigen::Vector3f e =
                    sampler.Emissive(s.original_face, w) / plan.emissive_scale;
                for (int c = 0; c < 3; ++c)
                  maps.emissive.pixels[3 * texel + c] = LinearToSrgbByte(e[c]);
              }
              if (plan.normal) {
                if (s.finest_face != frame_face) {
                  frame_face = s.finest_face;
                  frame = RemeshFrame(remesh, layout, frame_face, frame_usable);
                }
                Vec3 local(0, 0, 1);
                if (frame_usable) {
                  const Vec3 n = sampler.ObjectNormal(s.original_face, w);
                  local = {n.dot(frame.tangent), n.dot(frame.bitangent), n.dot(frame.normal)};
                  const double length = local.norm();
                  local = length > 0 ? Vec3(local / length) : Vec3(0, 0, 1);
                }
                for (int c = 0; c < 3; ++c) {
                  maps.normal.pixels[3 * texel + c] = UnitToByte(0.5 * (local[c] + 1));
                }
              }
            }
          }
        }
      },
      /*min_chunk=*/1);
  return maps;
}

bool AnyTranslucent(const BakedImage& rgba) {
  for (size_t i = 3; i < rgba.pixels.size(); i += 4) {
    if (rgba.pixels[i] != 255) return true;
  }
  return false;
}

// How a map's levels are coded: colour as lossy WebP (a third to half the
// bytes of JPEG at the same PSNR on baked atlases, docs/RD_RESULTS.md
// "Texture code"), alpha included; data whose channels are independent
// (occlusion, roughness, metallic) as 4:4:4 JPEG, which WebP's 4:2:0 lacks;
// normals as lossless PNG.
enum class MapCodec { kWebp, kJpeg444, kPng };

const char* MimeType(MapCodec codec) {
  switch (codec) {
    case MapCodec::kWebp: return "image/webp";
    case MapCodec::kJpeg444: return "image/jpeg";
    case MapCodec::kPng: return "image/png";
  }
  return "";
}

struct MapJob {
  TextureRole role;
  TexelKind kind;
  BakedImage full;
  MapCodec codec;
};

}  // namespace

Result<std::optional<BakedTexture>> BakeTexture(const MeshAsset& asset,
                                                const SemiRegularMesh& remesh,
                                                const TextureBakeOptions& options,
                                                TextureBakeNotes* notes) {
  MW_RETURN_IF_ERROR(CheckAsset(asset));
  if (remesh.hierarchy == nullptr || remesh.hierarchy->faces(0).empty()) {
    return InvalidArgument("texture bake: the remesh has no base faces");
  }
  if (remesh.positions.size() != remesh.hierarchy->vertex_count(remesh.levels())) {
    return InvalidArgument("texture bake: the remesh's positions do not fit its hierarchy");
  }
  if (options.quality < 1 || options.quality > 100) {
    return InvalidArgument("texture bake: quality " + std::to_string(options.quality) +
                           " (1..100)");
  }
  if (options.cell != 0 &&
      (options.cell < 16 || options.cell > 4096 || (options.cell & (options.cell - 1)) != 0)) {
    return InvalidArgument("texture bake: cell of " + std::to_string(options.cell) +
                           " texels (a power of two from 16 to 4096)");
  }
  const MaterialSampler sampler(asset);
  const BakePlan plan = PlanBake(asset, sampler);
  if (!plan.any_texture && plan.alike) return std::optional<BakedTexture>();

  const auto base_faces = static_cast<uint32_t>(remesh.hierarchy->faces(0).size());
  MW_ASSIGN_OR_RETURN(const AtlasPlan atlas_plan,
                      PlanAtlas(base_faces, TexelsOfOriginal(asset), options));
  MW_ASSIGN_OR_RETURN(const AtlasLayout layout,
                      AtlasLayout::Create(base_faces, atlas_plan.cell, atlas_plan.gutter));
  const int threads = ResolveThreads(options.threads);
  Maps maps = BakeMaps(asset, remesh, layout, plan, sampler, threads);

  BakedTexture out;
  out.atlas = {layout.cell(), layout.gutter(), layout.columns()};
  const Material& first = *plan.materials.front();
  TextureMaterial& material = out.material;
  material.metallic_factor = plan.metallic_roughness ? 1.0f : first.metallic_factor;
  material.roughness_factor = plan.metallic_roughness ? 1.0f : first.roughness_factor;
  material.emissive_factor =
      plan.emissive ? Eigen::Vector3f::Constant(plan.emissive_scale) : first.emissive_factor;
  material.normal_scale = 1.0f;
  material.occlusion_strength = 1.0f;
  const bool translucent = AnyTranslucent(maps.base_color);
  for (const Material* m : plan.materials) {
    material.double_sided = material.double_sided || m->double_sided;
    material.alpha_blend = material.alpha_blend || (m->alpha_mode != AlphaMode::kOpaque);
  }
  material.alpha_blend = material.alpha_blend && translucent;

  std::vector<MapJob> jobs;
  jobs.push_back({TextureRole::kBaseColor, TexelKind::kSrgbColor, std::move(maps.base_color),
                  MapCodec::kWebp});
  if (plan.metallic_roughness) {
    jobs.push_back({TextureRole::kMetallicRoughness, TexelKind::kLinear, std::move(maps.orm),
                    MapCodec::kJpeg444});
  }
  if (plan.emissive) {
    jobs.push_back({TextureRole::kEmissive, TexelKind::kSrgbColor, std::move(maps.emissive),
                    MapCodec::kWebp});
  }
  if (plan.normal) {
    jobs.push_back(
        {TextureRole::kNormal, TexelKind::kNormal, std::move(maps.normal), MapCodec::kPng});
  }
  const int levels = atlas_plan.levels;
  // Each map's pyramid in one task; the encodings of its levels are
  // independent of which thread makes them.
  std::vector<std::vector<Result<std::string>>> encoded(jobs.size());
  ParallelTasks(jobs.size(), threads, [&](size_t i) {
    MapJob& job = jobs[i];
    std::vector<Result<std::string>>& levels_out = encoded[i];
    BakedImage image = std::move(job.full);
    for (int level = 0; level < levels; ++level) {
      if (level > 0) image = HalveImage(image, job.kind);
      ImageView view{image.pixels.data(), image.width, image.height, image.channels};
      switch (job.codec) {
        case MapCodec::kWebp: levels_out.push_back(EncodeWebp(view, options.quality)); break;
        case MapCodec::kJpeg444:
          levels_out.push_back(EncodeJpeg(view, {options.quality, false}));
          break;
        case MapCodec::kPng: levels_out.push_back(EncodePng(view)); break;
      }
    }
  });
  for (size_t i = 0; i < jobs.size(); ++i) {
    TextureMap map;
    map.role = jobs[i].role;
    map.mime_type = MimeType(jobs[i].codec);
    for (auto it = encoded[i].rbegin(); it != encoded[i].rend(); ++it) {
      MW_RETURN_IF_ERROR(it->status());
      map.levels.push_back(std::move(**it));
    }
    out.maps.push_back(std::move(map));
  }

  if (notes != nullptr) {
    for (const std::string& line : asset.notes) {
      if (line.find("KHR_materials") != std::string::npos) {
        notes->lines.push_back("not baked: " + line);
      }
    }
    if (plan.materials.size() > 1) {
      notes->lines.push_back(std::to_string(plan.materials.size()) +
                             " materials baked into one set of maps");
    }
    for (const Material* m : plan.materials) {
      if (m->alpha_mode == AlphaMode::kMask) {
        notes->lines.push_back("material \"" + m->name + "\": alpha mask cut at " +
                               std::to_string(m->alpha_cutoff) + " into alpha 0 or 1");
      }
    }
    if (asset.uv.empty() && plan.any_texture) {
      notes->lines.push_back("no texture coordinates: textures sampled at UV (0, 0)");
    }
  }
  return std::optional<BakedTexture>(std::move(out));
}

}  // namespace meshwave
