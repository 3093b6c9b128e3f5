// SerializeTexturedGltf (meshwave/gltf.h): a textured mesh as glTF 2.0.
#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "core/base64.h"
#include "core/byte_reader.h"
#include "meshwave/gltf.h"

namespace meshwave {
namespace {

template <class T>
void AppendBytes(std::string& out, T value) {
  if constexpr (std::endian::native != std::endian::little) value = ByteSwapped(value);
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

void AppendJsonNumber(std::string& out, double value) {
  char buffer[32];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out.append(buffer, end);
}

void AppendJsonNumber(std::string& out, uint64_t value) {
  char buffer[24];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out.append(buffer, end);
}

void PadToFour(std::string& s, char pad) { s.append((4 - s.size() % 4) % 4, pad); }

// The written vertices: each (vertex, UV) pair met at a corner once.
struct SplitVertices {
  std::vector<uint32_t> source;          // per written vertex: its mesh vertex
  std::vector<std::array<float, 2>> uv;  // per written vertex
  std::vector<uint32_t> corner;          // per face corner: its written vertex
};

SplitVertices Split(const TriMesh& mesh, std::span<const float> corner_uvs) {
  constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();
  SplitVertices out;
  // Per mesh vertex the first of its written vertices, each the next.
  std::vector<uint32_t> first(mesh.positions.size(), kNone), next;
  out.corner.reserve(3 * mesh.faces.size());
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    for (size_t i = 0; i < 3; ++i) {
      const uint32_t v = mesh.faces[f][i];
      const std::array<float, 2> uv{corner_uvs[6 * f + 2 * i], corner_uvs[6 * f + 2 * i + 1]};
      uint32_t* link = &first[v];
      // Compared bit for bit: the atlas gives a vertex inside a base face
      // one exact value.
      while (*link != kNone && std::memcmp(out.uv[*link].data(), uv.data(), sizeof uv) != 0) {
        link = &next[*link];
      }
      if (*link == kNone) {
        *link = static_cast<uint32_t>(out.source.size());
        out.source.push_back(v);
        out.uv.push_back(uv);
      }
      // Read before `next` grows: `link` may point into it.
      const uint32_t written = *link;
      if (written == next.size()) next.push_back(kNone);
      out.corner.push_back(written);
    }
  }
  return out;
}

// Per written vertex a unit normal and a unit tangent with its handedness
// (w = ±1), as glTF's NORMAL and TANGENT: normals area-weighted over the
// faces around the mesh vertex (the same on both sides of a UV cut);
// tangents the direction of increasing u, from each face's UV gradient
// (Lengyel, "Computing Tangent Space Basis Vectors for an Arbitrary Mesh",
// 2001), summed per written vertex and made orthogonal to the normal.
struct TangentSpace {
  std::vector<Eigen::Vector3f> normals;
  std::vector<Eigen::Vector4f> tangents;
};

Eigen::Vector3d AnyPerpendicular(const Eigen::Vector3d& n) {
  const Eigen::Vector3d other =
      std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return n.cross(other).normalized();
}

TangentSpace ComputeTangentSpace(const TriMesh& mesh, const SplitVertices& split) {
  std::vector<Eigen::Vector3d> vertex_normal(mesh.positions.size(), Eigen::Vector3d::Zero());
  const size_t n = split.source.size();
  std::vector<Eigen::Vector3d> t(n, Eigen::Vector3d::Zero()), b(n, Eigen::Vector3d::Zero());
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const Face& face = mesh.faces[f];
    const Vec3 e1 = mesh.positions[face[1]] - mesh.positions[face[0]];
    const Vec3 e2 = mesh.positions[face[2]] - mesh.positions[face[0]];
    const Vec3 area_normal = e1.cross(e2);  // twice the area, outward
    for (uint32_t v : face) vertex_normal[v] += area_normal;
    const std::array<uint32_t, 3> w = {split.corner[3 * f], split.corner[3 * f + 1],
                                       split.corner[3 * f + 2]};
    const double du1 = split.uv[w[1]][0] - split.uv[w[0]][0];
    const double dv1 = split.uv[w[1]][1] - split.uv[w[0]][1];
    const double du2 = split.uv[w[2]][0] - split.uv[w[0]][0];
    const double dv2 = split.uv[w[2]][1] - split.uv[w[0]][1];
    const double det = du1 * dv2 - du2 * dv1;
    if (det == 0) continue;  // no UV area: no direction
    const Vec3 tangent = (e1 * dv2 - e2 * dv1) / det;
    const Vec3 bitangent = (e2 * du1 - e1 * du2) / det;
    for (uint32_t k : w) {
      t[k] += tangent;
      b[k] += bitangent;
    }
  }
  TangentSpace out;
  out.normals.reserve(n);
  out.tangents.reserve(n);
  for (size_t k = 0; k < n; ++k) {
    Eigen::Vector3d normal = vertex_normal[split.source[k]];
    normal = normal.norm() > 0 ? normal.normalized() : Eigen::Vector3d::UnitZ();
    Eigen::Vector3d tangent = t[k] - normal * normal.dot(t[k]);
    const double length = tangent.norm();
    tangent = length > 1e-12 ? Eigen::Vector3d(tangent / length) : AnyPerpendicular(normal);
    const float handedness = normal.cross(tangent).dot(b[k]) < 0 ? -1.0f : 1.0f;
    out.normals.push_back(normal.cast<float>());
    out.tangents.emplace_back(static_cast<float>(tangent.x()), static_cast<float>(tangent.y()),
                              static_cast<float>(tangent.z()), handedness);
  }
  return out;
}

const char* MaterialSlot(TextureRole role) {
  switch (role) {
    case TextureRole::kBaseColor: return "baseColorTexture";
    case TextureRole::kMetallicRoughness: return "metallicRoughnessTexture";
    case TextureRole::kNormal: return "normalTexture";
    case TextureRole::kOcclusion: return "occlusionTexture";
    case TextureRole::kEmissive: return "emissiveTexture";
  }
  return "";
}

}  // namespace

size_t TexturedVertexCount(const TriMesh& mesh, std::span<const float> corner_uvs) {
  if (corner_uvs.size() != 6 * mesh.faces.size()) return mesh.positions.size();
  return Split(mesh, corner_uvs).source.size();
}

std::string SerializeTexturedGltf(const TriMesh& mesh, GltfForm form,
                                  std::span<const float> corner_uvs,
                                  std::span<const TextureImage> images,
                                  const TextureMaterial& material,
                                  std::span<const Vec3> colors) {
  if (mesh.faces.empty() || mesh.positions.empty() || images.empty() ||
      corner_uvs.size() != 6 * mesh.faces.size()) {
    return SerializeGltf(mesh, form, colors);
  }
  const bool colored = colors.size() == mesh.positions.size();
  const SplitVertices split = Split(mesh, corner_uvs);
  const size_t n = split.source.size();
  // The buffer: positions, indices, UVs, colours, then each image (each
  // view 4-aligned).
  std::string bin;
  std::array<float, 3> lo, hi;
  lo.fill(std::numeric_limits<float>::infinity());
  hi.fill(-std::numeric_limits<float>::infinity());
  for (uint32_t v : split.source) {
    for (int a = 0; a < 3; ++a) {
      const float x = static_cast<float>(mesh.positions[v][a]);
      lo[a] = std::min(lo[a], x);
      hi[a] = std::max(hi[a], x);
      AppendBytes(bin, x);
    }
  }
  struct View {
    size_t offset, length;
  };
  std::vector<View> views{{0, bin.size()}};
  for (uint32_t c : split.corner) AppendBytes(bin, c);
  views.push_back({views.back().length, bin.size() - views.back().length});
  for (const auto& uv : split.uv) {
    AppendBytes(bin, uv[0]);
    AppendBytes(bin, uv[1]);
  }
  views.push_back({views[1].offset + views[1].length, 8 * n});
  // Further vertex attributes, each a FLOAT accessor of its own view.
  struct Attribute {
    const char* name;
    const char* type;
    size_t components;
  };
  std::vector<Attribute> attributes;
  auto add_view = [&](size_t bytes) {
    views.push_back({views.back().offset + views.back().length, bytes});
  };
  if (colored) {
    for (uint32_t v : split.source) {
      for (int a = 0; a < 3; ++a) AppendBytes(bin, static_cast<float>(std::clamp(colors[v][a], 0.0, 1.0)));
    }
    add_view(12 * n);
    attributes.push_back({"COLOR_0", "VEC3", 3});
  }
  // A normal map needs a tangent space: the file carries it (NORMAL and
  // TANGENT) rather than leave each viewer to make up its own.
  const bool normal_map = std::any_of(images.begin(), images.end(), [](const TextureImage& i) {
    return i.role == TextureRole::kNormal;
  });
  if (normal_map) {
    const TangentSpace space = ComputeTangentSpace(mesh, split);
    for (const Eigen::Vector3f& normal : space.normals) {
      for (int a = 0; a < 3; ++a) AppendBytes(bin, normal[a]);
    }
    add_view(12 * n);
    attributes.push_back({"NORMAL", "VEC3", 3});
    for (const Eigen::Vector4f& tangent : space.tangents) {
      for (int a = 0; a < 4; ++a) AppendBytes(bin, tangent[a]);
    }
    add_view(16 * n);
    attributes.push_back({"TANGENT", "VEC4", 4});
  }
  const size_t image_views = views.size();
  for (const TextureImage& image : images) {
    PadToFour(bin, '\0');
    views.push_back({bin.size(), image.bytes.size()});
    bin.append(image.bytes);
  }

  std::string json = R"({"asset":{"version":"2.0","generator":"meshwave"},"scene":0,)";
  // A WebP image needs EXT_texture_webp (glTF 2.0 core knows PNG and JPEG
  // only); required, as no fallback image travels.
  bool webp = false;
  for (const TextureImage& image : images) webp = webp || image.mime_type == "image/webp";
  if (webp) {
    json += R"("extensionsUsed":["EXT_texture_webp"],"extensionsRequired":["EXT_texture_webp"],)";
  }
  json += R"("scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)";
  json += R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":2)";
  for (size_t a = 0; a < attributes.size(); ++a) {
    json += std::string(",\"") + attributes[a].name + "\":";
    AppendJsonNumber(json, uint64_t{3 + a});
  }
  json += R"(},"indices":1,"material":0,"mode":4}]}],)";
  json += R"("accessors":[{"bufferView":0,"componentType":5126,"count":)";
  AppendJsonNumber(json, uint64_t{n});
  json += R"(,"type":"VEC3","min":[)";
  for (int a = 0; a < 3; ++a) {
    if (a) json += ',';
    AppendJsonNumber(json, static_cast<double>(lo[a]));
  }
  json += R"(],"max":[)";
  for (int a = 0; a < 3; ++a) {
    if (a) json += ',';
    AppendJsonNumber(json, static_cast<double>(hi[a]));
  }
  json += R"(]},{"bufferView":1,"componentType":5125,"count":)";
  AppendJsonNumber(json, uint64_t{split.corner.size()});
  json += R"(,"type":"SCALAR"},{"bufferView":2,"componentType":5126,"count":)";
  AppendJsonNumber(json, uint64_t{n});
  json += R"(,"type":"VEC2"})";
  for (size_t a = 0; a < attributes.size(); ++a) {
    json += R"(,{"bufferView":)";
    AppendJsonNumber(json, uint64_t{3 + a});
    json += R"(,"componentType":5126,"count":)";
    AppendJsonNumber(json, uint64_t{n});
    json += std::string(R"(,"type":")") + attributes[a].type + "\"}";
  }
  json += R"(],"bufferViews":[)";
  for (size_t i = 0; i < views.size(); ++i) {
    if (i) json += ',';
    json += R"({"buffer":0,"byteOffset":)";
    AppendJsonNumber(json, uint64_t{views[i].offset});
    json += R"(,"byteLength":)";
    AppendJsonNumber(json, uint64_t{views[i].length});
    // Vertex attributes and indices name their targets; images none.
    if (i < image_views) json += i == 1 ? R"(,"target":34963})" : R"(,"target":34962})";
    else json += '}';
  }
  json += R"(],"buffers":[{"byteLength":)";
  AppendJsonNumber(json, uint64_t{bin.size()});
  if (form == GltfForm::kEmbedded) {
    json += R"(,"uri":"data:application/octet-stream;base64,)";
    json += Base64(bin);
    json += '"';
  }
  json += "}]";
  // The material: each map a texture of its own image, one sampler.
  std::string pbr = R"("metallicFactor":)";
  AppendJsonNumber(pbr, static_cast<double>(material.metallic_factor));
  pbr += R"(,"roughnessFactor":)";
  AppendJsonNumber(pbr, static_cast<double>(material.roughness_factor));
  std::string rest;
  for (size_t i = 0; i < images.size(); ++i) {
    const TextureRole role = images[i].role;
    std::string slot = std::string(",\"") + MaterialSlot(role) + R"(":{"index":)";
    AppendJsonNumber(slot, uint64_t{i});
    if (role == TextureRole::kNormal) {
      slot += R"(,"scale":)";
      AppendJsonNumber(slot, static_cast<double>(material.normal_scale));
    } else if (role == TextureRole::kOcclusion) {
      slot += R"(,"strength":)";
      AppendJsonNumber(slot, static_cast<double>(material.occlusion_strength));
    }
    slot += '}';
    (role == TextureRole::kBaseColor || role == TextureRole::kMetallicRoughness ? pbr : rest) +=
        slot;
  }
  json += R"(,"materials":[{"pbrMetallicRoughness":{)" + pbr + "}" + rest;
  if (material.emissive_factor != Eigen::Vector3f::Zero()) {
    json += R"(,"emissiveFactor":[)";
    for (int c = 0; c < 3; ++c) {
      if (c) json += ',';
      AppendJsonNumber(json, static_cast<double>(material.emissive_factor[c]));
    }
    json += ']';
  }
  if (material.alpha_blend) json += R"(,"alphaMode":"BLEND")";
  if (material.double_sided) json += R"(,"doubleSided":true)";
  json += "}]";
  if (!images.empty()) {
    json += R"(,"samplers":[{"magFilter":9729,"minFilter":9987,"wrapS":33071,"wrapT":33071}])";
    json += R"(,"images":[)";
    for (size_t i = 0; i < images.size(); ++i) {
      if (i) json += ',';
      json += R"({"bufferView":)";
      AppendJsonNumber(json, uint64_t{image_views + i});
      json += R"(,"mimeType":")" + images[i].mime_type + "\"}";
    }
    json += R"(],"textures":[)";
    for (size_t i = 0; i < images.size(); ++i) {
      if (i) json += ',';
      if (images[i].mime_type == "image/webp") {
        json += R"({"sampler":0,"extensions":{"EXT_texture_webp":{"source":)";
        AppendJsonNumber(json, uint64_t{i});
        json += "}}}";
      } else {
        json += R"({"sampler":0,"source":)";
        AppendJsonNumber(json, uint64_t{i});
        json += '}';
      }
    }
    json += ']';
  }
  json += '}';
  if (form == GltfForm::kEmbedded) return json + "\n";

  // GLB: a 12-byte header, the JSON chunk (space-padded), the BIN chunk.
  PadToFour(json, ' ');
  PadToFour(bin, '\0');
  std::string out;
  out.reserve(28 + json.size() + bin.size());
  AppendBytes(out, uint32_t{0x46546C67});  // "glTF"
  AppendBytes(out, uint32_t{2});
  AppendBytes(out, static_cast<uint32_t>(28 + json.size() + bin.size()));
  AppendBytes(out, static_cast<uint32_t>(json.size()));
  AppendBytes(out, uint32_t{0x4E4F534A});  // "JSON"
  out += json;
  AppendBytes(out, static_cast<uint32_t>(bin.size()));
  AppendBytes(out, uint32_t{0x004E4942});  // "BIN\0"
  out += bin;
  return out;
}

}  // namespace meshwave
