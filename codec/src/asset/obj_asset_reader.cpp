// Wavefront OBJ with materials: v (with the common "v x y z r g b" vertex
// colours), vt, f in all its corner forms (v, v/vt, v//vn, v/vt/vn;
// negative indices relative), mtllib, usemtl; the MTL files and their
// textures come from the file set, relative to the OBJ. Polygons are
// fan-triangulated as ReadMesh does. Normals (vn), lines, points and
// free-form geometry are counted and noted, not carried.
#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "asset/asset_image.h"
#include "asset/asset_readers.h"
#include "asset/float_range.h"
#include "asset/mtl_reader.h"
#include "asset/srgb.h"
#include "asset/weld.h"
#include "mesh/mesh_readers.h"
#include "mesh/text_scanner.h"

namespace meshwave {
namespace {

constexpr uint32_t kNoUv = UINT32_MAX;

class ObjAssetParser {
 public:
  ObjAssetParser(std::string_view bytes, FileSet& files, std::string_view name,
                 const AssetLimits& limits)
      : files_(files), name_(name), limits_(limits), lines_(bytes) {}

  Result<MeshAsset> Parse() {
    std::string_view line;
    while (NextStatementLine(lines_, &line)) {
      TokenSplitter tokens(line);
      std::string_view keyword;
      if (!tokens.Next(&keyword)) continue;
      if (keyword == "v") {
        MW_RETURN_IF_ERROR(Vertex(tokens));
      } else if (keyword == "vt") {
        MW_RETURN_IF_ERROR(TexCoord(tokens));
      } else if (keyword == "vn") {
        ++normals_;
      } else if (keyword == "f") {
        MW_RETURN_IF_ERROR(FaceStatement(tokens));
      } else if (keyword == "mtllib") {
        MW_RETURN_IF_ERROR(MaterialLibrary(tokens));
      } else if (keyword == "usemtl") {
        UseMaterial(tokens);
      } else if (keyword == "l" || keyword == "p") {
        ++lines_and_points_;
      } else if (keyword == "curv" || keyword == "curv2" || keyword == "surf" ||
                 keyword == "cstype") {
        ++free_form_;
      }
    }
    MW_RETURN_IF_ERROR(CheckForwardReferences());
    if (asset_.mesh.faces.empty()) {
      return ParseError(std::string(name_) + ": no faces (" +
                        std::to_string(asset_.mesh.positions.size()) +
                        " vertices)");
    }
    MW_RETURN_IF_ERROR(Finish());
    return std::move(asset_);
  }

 private:
  struct Forward {
    size_t line;
    uint64_t index;  // 0-based
    bool uv;
  };

  Status Error(const std::string& what) const {
    return MeshParseError(name_, LineWhere(lines_.number()), what);
  }

  Status Vertex(TokenSplitter& tokens) {
    if (asset_.mesh.positions.size() >= limits_.max_vertices) {
      return Error("more than " + std::to_string(limits_.max_vertices) +
                   " vertices");
    }
    double v[7];
    size_t n = 0;
    std::string_view token;
    while (n < 7 && tokens.Next(&token)) {
      if (!ParseDouble(token, &v[n]))
        return Error("bad number " + Quoted(token));
      if (!std::isfinite(v[n])) {
        return Error("coordinate " + Quoted(token) + " is NaN or infinite");
      }
      ++n;
    }
    if (n < 3) return Error("vertex needs x, y and z");
    asset_.mesh.positions.emplace_back(v[0], v[1], v[2]);
    // "v x y z r g b" (MeshLab, ZBrush and others): sRGB-encoded colours
    // in [0, 1], like PLY's. Four or five numbers are x y z w (w ignored).
    if (n >= 6) {
      const size_t at = n == 7 ? 4 : 3;
      vertex_colors_.resize(asset_.mesh.positions.size(),
                            Eigen::Vector4f(1.0f, 1.0f, 1.0f, 1.0f));
      vertex_colors_.back() =
          Eigen::Vector4f(SrgbToLinear(v[at]), SrgbToLinear(v[at + 1]),
                          SrgbToLinear(v[at + 2]), 1.0f);
    }
    return Status::Ok();
  }

  Status TexCoord(TokenSplitter& tokens) {
    if (asset_.uv.values.size() >= limits_.max_vertices) {
      return Error("more than " + std::to_string(limits_.max_vertices) +
                   " texture coordinates");
    }
    double uv[2] = {0.0, 0.0};
    std::string_view token;
    int read = 0;
    for (; read < 2 && tokens.Next(&token); ++read) {
      if (!ParseDouble(token, &uv[read]) || !FitsFloat(uv[read])) {
        return Error("bad texture coordinate " + Quoted(token));
      }
    }
    if (read == 0) return Error("vt needs u (and usually v)");
    // OBJ's v grows upwards from the bottom row; glTF's downwards.
    asset_.uv.values.emplace_back(static_cast<float>(uv[0]),
                                  static_cast<float>(1.0 - uv[1]));
    return Status::Ok();
  }

  // Resolves a 1-based (or negative, relative) index among `count` so far.
  Status Resolve(std::string_view number, uint64_t count, bool uv,
                 uint32_t* out) {
    int64_t value = 0;
    if (!ParseInt64(number, &value)) {
      return Error(std::string("bad ") +
                   (uv ? "texture coordinate" : "vertex") + " index " +
                   Quoted(number));
    }
    if (value == 0) {
      return Error(std::string(uv ? "texture coordinate" : "vertex") +
                   " index 0 (OBJ indices start at 1)");
    }
    const int64_t resolved =
        value > 0 ? value - 1 : static_cast<int64_t>(count) + value;
    if (resolved < 0 || static_cast<uint64_t>(resolved) >= kMaxVertices) {
      return Error(std::string(uv ? "texture coordinate" : "vertex") +
                   " index " + std::to_string(value) + " out of range (" +
                   std::to_string(count) + " so far)");
    }
    if (static_cast<uint64_t>(resolved) >= count) {
      forward_.push_back(
          {lines_.number(), static_cast<uint64_t>(resolved), uv});
    }
    *out = static_cast<uint32_t>(resolved);
    return Status::Ok();
  }

  Status FaceStatement(TokenSplitter& tokens) {
    uint32_t v[3] = {0, 0, 0};
    uint32_t t[3] = {0, 0, 0};
    size_t n = 0;
    int with_uv = -1;  // unknown until the first corner
    std::string_view token;
    while (tokens.Next(&token)) {
      const size_t slash = token.find('/');
      uint32_t vi = 0;
      MW_RETURN_IF_ERROR(Resolve(token.substr(0, slash),
                                 asset_.mesh.positions.size(), false, &vi));
      uint32_t ti = kNoUv;
      if (slash != std::string_view::npos) {
        std::string_view rest = token.substr(slash + 1);
        const std::string_view uv = rest.substr(0, rest.find('/'));
        if (!uv.empty()) {
          MW_RETURN_IF_ERROR(Resolve(uv, asset_.uv.values.size(), true, &ti));
        }
      }
      const int has = ti != kNoUv;
      if (with_uv >= 0 && has != with_uv) {
        return Error("face mixes corners with and without texture coordinates");
      }
      with_uv = has;
      const size_t k = n < 2 ? n : 2;
      v[k] = vi;
      t[k] = ti;
      if (n >= 2) {
        if (asset_.mesh.faces.size() >= limits_.max_triangles) {
          return Error("more than " + std::to_string(limits_.max_triangles) +
                       " triangles");
        }
        asset_.mesh.faces.push_back({v[0], v[1], v[2]});
        asset_.uv.faces.push_back({t[0], t[1], t[2]});
        face_material_.push_back(material_);
        v[1] = v[2];  // fan around the first corner
        t[1] = t[2];
      }
      ++n;
    }
    if (n < 3) {
      return Error("face with " + std::to_string(n) +
                   " corners (at least 3 needed)");
    }
    return Status::Ok();
  }

  Status MaterialLibrary(TokenSplitter& tokens) {
    std::string rest(tokens.Rest());
    while (!rest.empty() && IsSpace(rest.back())) rest.pop_back();
    std::replace(rest.begin(), rest.end(), '\\', '/');
    // One name with spaces, or several names separated by spaces.
    std::vector<std::string> names;
    Result<std::string> whole = ResolveFileSetReference(name_, rest);
    if (whole.ok() && files_.Contains(*whole)) {
      names.push_back(*whole);
    } else {
      TokenSplitter parts(rest);
      std::string_view part;
      while (parts.Next(&part)) {
        Result<std::string> resolved = ResolveFileSetReference(name_, part);
        if (!resolved.ok()) {
          return resolved.status().WithContext(std::string(name_) + ": " +
                                               LineWhere(lines_.number()));
        }
        names.push_back(std::move(resolved).value());
      }
    }
    if (names.empty()) return Error("mtllib names no file");
    for (const std::string& file : names) {
      if (!loaded_libraries_.insert({file, true}).second) continue;
      Result<std::string_view> bytes = files_.Read(file);
      if (!bytes.ok()) {
        return bytes.status().WithContext(std::string(name_) + ": " +
                                          LineWhere(lines_.number()) +
                                          ": material library missing");
      }
      MW_ASSIGN_OR_RETURN(std::vector<MtlMaterial> parsed,
                          ParseMtl(*bytes, file, &asset_.notes));
      for (MtlMaterial& m : parsed) {
        // The first definition of a name wins, as in most readers.
        if (library_.count(m.material.name) == 0) {
          library_.emplace(m.material.name, std::move(m));
        }
      }
    }
    return Status::Ok();
  }

  void UseMaterial(TokenSplitter& tokens) {
    std::string name(tokens.Rest());
    while (!name.empty() && IsSpace(name.back())) name.pop_back();
    const auto it = used_.find(name);
    if (it != used_.end()) {
      material_ = it->second;
      return;
    }
    material_ = static_cast<int32_t>(used_.size());
    used_.emplace(name, material_);
    used_order_.push_back(name);
  }

  Status CheckForwardReferences() const {
    for (const Forward& f : forward_) {
      const uint64_t count =
          f.uv ? asset_.uv.values.size() : asset_.mesh.positions.size();
      if (f.index >= count) {
        return MeshParseError(
            name_, LineWhere(f.line),
            std::string(f.uv ? "texture coordinate" : "vertex") + " index " +
                std::to_string(f.index + 1) + " out of range (" +
                std::to_string(count) + (f.uv ? " vt lines)" : " vertices)"));
      }
    }
    return Status::Ok();
  }

  // The image index of a texture file, loading it once.
  Result<int32_t> Image(const std::string& file) {
    const auto it = image_index_.find(file);
    if (it != image_index_.end()) return it->second;
    Result<std::string_view> bytes = files_.Read(file);
    if (!bytes.ok()) {
      return bytes.status().WithContext(std::string(name_) + ": texture " +
                                        file + " is missing");
    }
    AssetImage image;
    image.name = file;
    image.encoded.assign(bytes->begin(), bytes->end());
    MW_RETURN_IF_ERROR(DecodeAssetImage(image, limits_, &decoded_left_));
    const auto index = static_cast<int32_t>(asset_.images.size());
    asset_.images.push_back(std::move(image));
    image_index_.emplace(file, index);
    return index;
  }

  Status Finish() {
    const std::string prefix = std::string(name_) + ": ";
    // Texture coordinates: faces without them index a shared (0, 0).
    size_t without_uv = 0;
    if (asset_.uv.values.empty()) {
      asset_.uv.faces.clear();
    } else {
      const uint32_t shared = static_cast<uint32_t>(asset_.uv.values.size());
      for (Face& f : asset_.uv.faces) {
        if (f[0] == kNoUv) {
          f = {shared, shared, shared};
          ++without_uv;
        }
      }
      if (without_uv > 0) {
        asset_.uv.values.emplace_back(0.0f, 0.0f);
        asset_.notes.push_back(
            prefix + std::to_string(without_uv) +
            " faces without texture coordinates get UV (0, 0)");
      }
    }
    // Vertex colours, per v line; corners index them by vertex number.
    if (!vertex_colors_.empty()) {
      vertex_colors_.resize(asset_.mesh.positions.size(),
                            Eigen::Vector4f(1.0f, 1.0f, 1.0f, 1.0f));
      asset_.color.values = std::move(vertex_colors_);
      asset_.color.faces = asset_.mesh.faces;
    }
    // Materials in the order usemtl first names them; faces before any
    // usemtl get a default one.
    if (!used_.empty()) {
      bool any_default = false;
      for (const std::string& name : used_order_) {
        const auto it = library_.find(name);
        if (it == library_.end()) {
          asset_.notes.push_back(prefix + "material \"" + name.substr(0, 60) +
                                 "\" is defined in no material library: "
                                 "white is used");
          Material m;
          m.name = name;
          m.metallic_factor = 0.0f;
          asset_.materials.push_back(m);
          continue;
        }
        MtlMaterial& entry = it->second;
        Material m = entry.material;
        if (!entry.base_color_file.empty()) {
          MW_ASSIGN_OR_RETURN(m.base_color_texture.image,
                              Image(entry.base_color_file));
        }
        if (!entry.normal_file.empty()) {
          MW_ASSIGN_OR_RETURN(m.normal_texture.image, Image(entry.normal_file));
        }
        if (!entry.emissive_file.empty()) {
          MW_ASSIGN_OR_RETURN(m.emissive_texture.image,
                              Image(entry.emissive_file));
        }
        asset_.materials.push_back(std::move(m));
      }
      const uint32_t fallback = static_cast<uint32_t>(asset_.materials.size());
      asset_.face_material.reserve(face_material_.size());
      for (int32_t m : face_material_) {
        if (m < 0) any_default = true;
        asset_.face_material.push_back(m >= 0 ? static_cast<uint32_t>(m)
                                              : fallback);
      }
      if (any_default) {
        Material m;
        m.name = "default";
        m.metallic_factor = 0.0f;
        asset_.materials.push_back(m);
      }
    }
    if (normals_ > 0) {
      asset_.notes.push_back(prefix + std::to_string(normals_) +
                             " vertex normals (vn) not carried (recomputed "
                             "from the surface)");
    }
    if (lines_and_points_ > 0) {
      asset_.notes.push_back(prefix + std::to_string(lines_and_points_) +
                             " line and point statements (l, p) not carried");
    }
    if (free_form_ > 0) {
      asset_.notes.push_back(prefix +
                             "free-form curves and surfaces not carried");
    }
    WeldPositions(asset_.mesh);
    return Status::Ok();
  }

  FileSet& files_;
  std::string_view name_;
  const AssetLimits& limits_;
  LineSplitter lines_;
  MeshAsset asset_;
  std::vector<Eigen::Vector4f> vertex_colors_;  // per v line; may be short
  std::vector<int32_t> face_material_;          // index into used_order_
  std::vector<Forward> forward_;
  std::map<std::string, bool> loaded_libraries_;
  std::map<std::string, MtlMaterial> library_;
  std::map<std::string, int32_t> used_;
  std::vector<std::string> used_order_;
  std::map<std::string, int32_t> image_index_;
  uint64_t decoded_left_ = limits_.max_image_bytes;
  int32_t material_ = -1;
  size_t normals_ = 0;
  size_t lines_and_points_ = 0;
  size_t free_form_ = 0;
};

}  // namespace

Result<MeshAsset> ParseObjAsset(std::string_view bytes, FileSet& files,
                                std::string_view main_name,
                                const AssetLimits& limits) {
  return ObjAssetParser(bytes, files, main_name, limits).Parse();
}

}  // namespace meshwave
