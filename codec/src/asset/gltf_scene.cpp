#include "asset/gltf_scene.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <utility>

#include "asset/gltf_accessor.h"

namespace meshwave {
namespace {

constexpr uint32_t kNoValue = UINT32_MAX;  // a face without the attribute

constexpr uint32_t kQuantizedMask =
    ComponentBit(TINYGLTF_COMPONENT_TYPE_BYTE) |
    ComponentBit(TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) |
    ComponentBit(TINYGLTF_COMPONENT_TYPE_SHORT) |
    ComponentBit(TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
constexpr uint32_t kFloatBit = ComponentBit(TINYGLTF_COMPONENT_TYPE_FLOAT);

// One primitive's data as stored, before any node transform.
struct PrimitiveData {
  std::vector<Vec3> positions;
  std::vector<Eigen::Vector2f> uvs;     // empty: no TEXCOORD_0
  std::vector<Eigen::Vector4f> colors;  // empty: no COLOR_0
  std::vector<Face> triangles;          // indices into the above
  bool clamped_colors = false;
};

struct Instance {
  int mesh;
  Eigen::Matrix4d world;
};

std::string MeshContext(const tinygltf::Model& model, int mesh, int primitive) {
  std::string out = "mesh " + std::to_string(mesh);
  const std::string& name = model.meshes[static_cast<size_t>(mesh)].name;
  if (!name.empty()) out += " \"" + name.substr(0, 60) + "\"";
  return out + " primitive " + std::to_string(primitive);
}

class SceneBuilder {
 public:
  SceneBuilder(const tinygltf::Model& model, std::string_view name,
               const AssetLimits& limits)
      : model_(model), name_(name), limits_(limits) {}

  Result<GltfGeometry> Build() {
    MW_ASSIGN_OR_RETURN(const std::vector<Instance> instances, Instances());
    for (const Instance& instance : instances) {
      const auto& mesh = model_.meshes[static_cast<size_t>(instance.mesh)];
      for (size_t p = 0; p < mesh.primitives.size(); ++p) {
        MW_RETURN_IF_ERROR(AddPrimitive(instance, static_cast<int>(p)));
      }
    }
    Finish();
    return std::move(out_);
  }

 private:
  Status Error(const std::string& what) const {
    return ParseError(std::string(name_) + ": " + what);
  }

  // ---- the node tree ----

  Result<Eigen::Matrix4d> LocalMatrix(int index) const {
    const tinygltf::Node& node = model_.nodes[static_cast<size_t>(index)];
    const std::string where = "node " + std::to_string(index);
    auto finite = [](const std::vector<double>& v) {
      return std::all_of(v.begin(), v.end(),
                         [](double x) { return std::isfinite(x); });
    };
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    if (!node.matrix.empty()) {
      if (node.matrix.size() != 16 || !finite(node.matrix)) {
        return Error(where + ": matrix needs 16 finite numbers");
      }
      for (int i = 0; i < 16; ++i) m(i % 4, i / 4) = node.matrix[i];  // columns
      return m;
    }
    const auto& t = node.translation;
    const auto& r = node.rotation;
    const auto& s = node.scale;
    if ((!t.empty() && (t.size() != 3 || !finite(t))) ||
        (!r.empty() && (r.size() != 4 || !finite(r))) ||
        (!s.empty() && (s.size() != 3 || !finite(s)))) {
      return Error(where +
                   ": translation, rotation and scale need 3, 4 and 3 finite "
                   "numbers");
    }
    if (!s.empty())
      m.topLeftCorner<3, 3>() = Eigen::Vector3d(s[0], s[1], s[2]).asDiagonal();
    if (!r.empty()) {
      // glTF quaternions are (x, y, z, w) and should be unit; normalise.
      Eigen::Quaterniond q(r[3], r[0], r[1], r[2]);
      if (q.norm() == 0.0)
        return Error(where + ": rotation is a zero quaternion");
      q.normalize();
      m.topLeftCorner<3, 3>() = q.toRotationMatrix() * m.topLeftCorner<3, 3>();
    }
    if (!t.empty())
      m.topRightCorner<3, 1>() = Eigen::Vector3d(t[0], t[1], t[2]);
    return m;
  }

  Result<std::vector<int>> SceneRoots() {
    const size_t node_count = model_.nodes.size();
    // Every child index in range, and no node with two parents.
    std::vector<int> parent(node_count, -1);
    for (size_t n = 0; n < node_count; ++n) {
      for (int child : model_.nodes[n].children) {
        if (child < 0 || static_cast<size_t>(child) >= node_count) {
          return Error("node " + std::to_string(n) + " has child " +
                       std::to_string(child) + ", the file has " +
                       std::to_string(node_count) + " nodes");
        }
        if (parent[static_cast<size_t>(child)] >= 0) {
          return Error(
              "node " + std::to_string(child) + " has two parents (nodes " +
              std::to_string(parent[static_cast<size_t>(child)]) + " and " +
              std::to_string(n) + "); glTF nodes form trees");
        }
        parent[static_cast<size_t>(child)] = static_cast<int>(n);
      }
    }
    if (model_.scenes.empty()) {
      std::vector<int> roots;
      for (size_t n = 0; n < node_count; ++n) {
        if (parent[n] < 0) roots.push_back(static_cast<int>(n));
      }
      if (!roots.empty()) {
        out_.notes.push_back(std::string(name_) +
                             ": no scene; every root node was read");
      }
      return roots;
    }
    const int scene = model_.defaultScene >= 0 ? model_.defaultScene : 0;
    if (static_cast<size_t>(scene) >= model_.scenes.size()) {
      return Error("the default scene is " + std::to_string(scene) +
                   ", the file has " + std::to_string(model_.scenes.size()));
    }
    if (model_.scenes.size() > 1) {
      out_.notes.push_back(std::string(name_) + ": scene " +
                           std::to_string(scene) + " of " +
                           std::to_string(model_.scenes.size()) +
                           " read; the other scenes are not carried");
    }
    for (int n : model_.scenes[static_cast<size_t>(scene)].nodes) {
      if (n < 0 || static_cast<size_t>(n) >= node_count) {
        return Error("scene " + std::to_string(scene) + " lists node " +
                     std::to_string(n) + ", the file has " +
                     std::to_string(node_count));
      }
    }
    return model_.scenes[static_cast<size_t>(scene)].nodes;
  }

  Result<std::vector<Instance>> Instances() {
    MW_ASSIGN_OR_RETURN(const std::vector<int> roots, SceneRoots());
    struct Pending {
      int node;
      Eigen::Matrix4d parent_world;
      uint32_t depth;
    };
    std::vector<Pending> stack;
    for (auto it = roots.rbegin(); it != roots.rend(); ++it) {
      stack.push_back({*it, Eigen::Matrix4d::Identity(), 1});
    }
    std::vector<bool> visited(model_.nodes.size(), false);
    std::vector<Instance> instances;
    while (!stack.empty()) {
      const Pending p = stack.back();
      stack.pop_back();
      const size_t n = static_cast<size_t>(p.node);
      if (visited[n]) {
        return Error("node " + std::to_string(n) +
                     " is reached twice from the scene: a cycle in the node "
                     "tree, or a node listed twice");
      }
      visited[n] = true;
      if (p.depth > limits_.max_node_depth) {
        return Error("the node tree is deeper than " +
                     std::to_string(limits_.max_node_depth) + " levels");
      }
      MW_ASSIGN_OR_RETURN(const Eigen::Matrix4d local, LocalMatrix(p.node));
      const Eigen::Matrix4d world = p.parent_world * local;
      const tinygltf::Node& node = model_.nodes[n];
      if (node.mesh >= 0) {
        if (static_cast<size_t>(node.mesh) >= model_.meshes.size()) {
          return Error("node " + std::to_string(n) + " draws mesh " +
                       std::to_string(node.mesh) + ", the file has " +
                       std::to_string(model_.meshes.size()));
        }
        instances.push_back({node.mesh, world});
      }
      for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) {
        stack.push_back({*it, world, p.depth + 1});
      }
    }
    std::set<int> drawn;
    for (const Instance& i : instances) drawn.insert(i.mesh);
    const size_t undrawn = model_.meshes.size() - drawn.size();
    if (undrawn > 0) {
      out_.notes.push_back(std::string(name_) + ": " + std::to_string(undrawn) +
                           " mesh" + (undrawn == 1 ? "" : "es") +
                           " not drawn by any node of the scene, not read");
    }
    return instances;
  }

  // ---- primitives ----

  Result<PrimitiveData> ReadPrimitive(int mesh_index, int primitive_index,
                                      int mode) {
    const tinygltf::Primitive& prim =
        model_.meshes[static_cast<size_t>(mesh_index)]
            .primitives[static_cast<size_t>(primitive_index)];
    const std::string context =
        std::string(name_) + ": " +
        MeshContext(model_, mesh_index, primitive_index);
    PrimitiveData data;
    AccessorSpec position{"POSITION", TypeBit(3), kFloatBit | kQuantizedMask,
                          kQuantizedMask, limits_.max_vertices};
    MW_ASSIGN_OR_RETURN(const AccessorValues p,
                        ReadAccessor(model_, prim.attributes.at("POSITION"),
                                     position, context));
    data.positions.resize(p.count);
    for (size_t i = 0; i < p.count; ++i) {
      data.positions[i] =
          Vec3(p.values[3 * i], p.values[3 * i + 1], p.values[3 * i + 2]);
      if (!data.positions[i].allFinite()) {
        return ParseError(context + ": POSITION of vertex " +
                          std::to_string(i) + " is NaN or infinite");
      }
    }
    if (const auto it = prim.attributes.find("TEXCOORD_0");
        it != prim.attributes.end()) {
      AccessorSpec uv{"TEXCOORD_0", TypeBit(2), kFloatBit | kQuantizedMask,
                      kQuantizedMask, limits_.max_vertices};
      MW_ASSIGN_OR_RETURN(const AccessorValues t,
                          ReadAccessor(model_, it->second, uv, context));
      MW_RETURN_IF_ERROR(CheckCount(context, "TEXCOORD_0", t.count, p.count));
      data.uvs.resize(t.count);
      for (size_t i = 0; i < t.count; ++i) {
        data.uvs[i] = Eigen::Vector2f(static_cast<float>(t.values[2 * i]),
                                      static_cast<float>(t.values[2 * i + 1]));
        if (!data.uvs[i].allFinite()) {
          return ParseError(context + ": TEXCOORD_0 of vertex " +
                            std::to_string(i) + " is NaN or infinite");
        }
      }
    }
    if (const auto it = prim.attributes.find("COLOR_0");
        it != prim.attributes.end()) {
      AccessorSpec color{
          "COLOR_0", TypeBit(3) | TypeBit(4), kFloatBit,
          ComponentBit(TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) |
              ComponentBit(TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT),
          limits_.max_vertices};
      MW_ASSIGN_OR_RETURN(const AccessorValues c,
                          ReadAccessor(model_, it->second, color, context));
      MW_RETURN_IF_ERROR(CheckCount(context, "COLOR_0", c.count, p.count));
      data.colors.resize(c.count);
      for (size_t i = 0; i < c.count; ++i) {
        Eigen::Vector4f rgba(1.0f, 1.0f, 1.0f, 1.0f);
        for (int k = 0; k < c.components; ++k) {
          const double v = c.values[i * c.components + k];
          if (!std::isfinite(v)) {
            return ParseError(context + ": COLOR_0 of vertex " +
                              std::to_string(i) + " is NaN or infinite");
          }
          if (v < 0.0 || v > 1.0) data.clamped_colors = true;
          rgba[k] = static_cast<float>(std::clamp(v, 0.0, 1.0));
        }
        data.colors[i] = rgba;
      }
    }
    MW_RETURN_IF_ERROR(ReadTriangles(prim, mode, p.count, context, data));
    return data;
  }

  static Status CheckCount(const std::string& context, const char* what,
                           size_t count, size_t positions) {
    if (count == positions) return Status::Ok();
    return ParseError(context + ": " + what + " has " + std::to_string(count) +
                      " elements, POSITION " + std::to_string(positions));
  }

  Status ReadTriangles(const tinygltf::Primitive& prim, int mode,
                       size_t vertex_count, const std::string& context,
                       PrimitiveData& data) {
    std::vector<uint32_t> indices;
    if (prim.indices >= 0) {
      AccessorSpec spec{
          "indices", TypeBit(1),
          ComponentBit(TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) |
              ComponentBit(TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) |
              ComponentBit(TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT),
          0, limits_.max_triangles * 3};
      MW_ASSIGN_OR_RETURN(const AccessorValues v,
                          ReadAccessor(model_, prim.indices, spec, context));
      indices.resize(v.count);
      for (size_t i = 0; i < v.count; ++i) {
        if (v.values[i] >= static_cast<double>(vertex_count)) {
          return ParseError(context + ": index " +
                            std::to_string(static_cast<uint64_t>(v.values[i])) +
                            " out of range (" + std::to_string(vertex_count) +
                            " vertices)");
        }
        indices[i] = static_cast<uint32_t>(v.values[i]);
      }
    } else {
      if (vertex_count > UINT32_MAX) {
        return ParseError(context +
                          ": more vertices than 32-bit indices address");
      }
      indices.resize(vertex_count);
      for (size_t i = 0; i < vertex_count; ++i)
        indices[i] = static_cast<uint32_t>(i);
    }
    const size_t n = indices.size();
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      if (n % 3 != 0) {
        return ParseError(context + ": " + std::to_string(n) +
                          " indices for TRIANGLES, not a multiple of 3");
      }
      data.triangles.reserve(n / 3);
      for (size_t i = 0; i + 2 < n; i += 3) {
        data.triangles.push_back({indices[i], indices[i + 1], indices[i + 2]});
      }
    } else if (n >= 3) {
      data.triangles.reserve(n - 2);
      for (size_t i = 0; i + 2 < n; ++i) {
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
          // glTF 2.0 section 3.7.2.1: every other triangle swaps two corners
          // so that all keep the strip's winding.
          const size_t odd = i % 2;
          data.triangles.push_back(
              {indices[i], indices[i + 1 + odd], indices[i + 2 - odd]});
        } else {  // TRIANGLE_FAN
          data.triangles.push_back(
              {indices[i + 1], indices[i + 2], indices[0]});
        }
      }
    }
    return Status::Ok();
  }

  void NoteAttributes(const tinygltf::Primitive& prim) {
    for (const auto& [attribute, accessor] : prim.attributes) {
      if (attribute == "POSITION" || attribute == "TEXCOORD_0" ||
          attribute == "COLOR_0") {
        continue;
      }
      ++dropped_attributes_[attribute];
    }
    if (!prim.targets.empty()) ++morphed_primitives_;
  }

  Status AddPrimitive(const Instance& instance, int primitive_index) {
    const auto& prim = model_.meshes[static_cast<size_t>(instance.mesh)]
                           .primitives[static_cast<size_t>(primitive_index)];
    const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    const std::string context =
        std::string(name_) + ": " +
        MeshContext(model_, instance.mesh, primitive_index);
    if (mode == TINYGLTF_MODE_POINTS || mode == TINYGLTF_MODE_LINE ||
        mode == TINYGLTF_MODE_LINE_LOOP || mode == TINYGLTF_MODE_LINE_STRIP) {
      ++point_line_primitives_;
      return Status::Ok();
    }
    if (mode != TINYGLTF_MODE_TRIANGLES &&
        mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        mode != TINYGLTF_MODE_TRIANGLE_FAN) {
      return ParseError(context + ": unknown primitive mode " +
                        std::to_string(mode));
    }
    if (prim.attributes.count("POSITION") == 0) {
      ++positionless_primitives_;
      return Status::Ok();
    }
    if (prim.material >= 0 &&
        static_cast<size_t>(prim.material) >= model_.materials.size()) {
      return ParseError(context + ": material " +
                        std::to_string(prim.material) +
                        " does not exist (the file has " +
                        std::to_string(model_.materials.size()) + ")");
    }
    const auto key = std::make_pair(instance.mesh, primitive_index);
    auto cached = cache_.find(key);
    if (cached == cache_.end()) {
      MW_ASSIGN_OR_RETURN(PrimitiveData data,
                          ReadPrimitive(instance.mesh, primitive_index, mode));
      NoteAttributes(prim);
      cached = cache_.emplace(key, std::move(data)).first;
    }
    const PrimitiveData& data = cached->second;
    if (data.clamped_colors) clamped_colors_ = true;

    TriMesh& mesh = out_.mesh;
    if (mesh.positions.size() + data.positions.size() > limits_.max_vertices ||
        mesh.faces.size() + data.triangles.size() > limits_.max_triangles) {
      return Status(StatusCode::kUnsupported,
                    std::string(name_) + ": the scene draws more than " +
                        std::to_string(limits_.max_vertices) + " vertices or " +
                        std::to_string(limits_.max_triangles) +
                        " triangles (counting every node that draws a mesh)");
    }
    const uint32_t base = static_cast<uint32_t>(mesh.positions.size());
    const Eigen::Matrix3d linear = instance.world.topLeftCorner<3, 3>();
    const Eigen::Vector3d offset = instance.world.topRightCorner<3, 1>();
    for (size_t i = 0; i < data.positions.size(); ++i) {
      const Vec3 p = linear * data.positions[i] + offset;
      if (!p.allFinite()) {
        return ParseError(context + ": vertex " + std::to_string(i) +
                          " is infinite after its node transform");
      }
      mesh.positions.push_back(p);
    }
    const bool flip = linear.determinant() < 0.0;
    const uint32_t uv_base = static_cast<uint32_t>(out_.uv.values.size());
    const uint32_t color_base = static_cast<uint32_t>(out_.color.values.size());
    out_.uv.values.insert(out_.uv.values.end(), data.uvs.begin(),
                          data.uvs.end());
    out_.color.values.insert(out_.color.values.end(), data.colors.begin(),
                             data.colors.end());
    for (Face f : data.triangles) {
      if (flip) std::swap(f[1], f[2]);
      mesh.faces.push_back({base + f[0], base + f[1], base + f[2]});
      out_.uv.faces.push_back(
          data.uvs.empty()
              ? Face{kNoValue, kNoValue, kNoValue}
              : Face{uv_base + f[0], uv_base + f[1], uv_base + f[2]});
      out_.color.faces.push_back(
          data.colors.empty()
              ? Face{kNoValue, kNoValue, kNoValue}
              : Face{color_base + f[0], color_base + f[1], color_base + f[2]});
      out_.face_material.push_back(prim.material);
    }
    return Status::Ok();
  }

  // Faces of parts without an attribute index a shared default value; an
  // attribute no part has is left empty.
  template <class T>
  static void FillDefaults(CornerAttribute<T>& attribute, const T& fallback) {
    if (attribute.values.empty()) {
      attribute.faces.clear();
      return;
    }
    const uint32_t shared = static_cast<uint32_t>(attribute.values.size());
    bool used = false;
    for (Face& f : attribute.faces) {
      if (f[0] == kNoValue) {
        f = {shared, shared, shared};
        used = true;
      }
    }
    if (used) attribute.values.push_back(fallback);
  }

  void Finish() {
    FillDefaults(out_.uv, Eigen::Vector2f(0.0f, 0.0f));
    FillDefaults(out_.color, Eigen::Vector4f(1.0f, 1.0f, 1.0f, 1.0f));
    const std::string prefix = std::string(name_) + ": ";
    if (point_line_primitives_ > 0) {
      out_.notes.push_back(prefix + std::to_string(point_line_primitives_) +
                           " point or line primitive(s) not carried (only "
                           "triangles are)");
    }
    if (positionless_primitives_ > 0) {
      out_.notes.push_back(prefix + std::to_string(positionless_primitives_) +
                           " primitive(s) without POSITION skipped");
    }
    if (morphed_primitives_ > 0) {
      out_.notes.push_back(
          prefix + "morph targets of " + std::to_string(morphed_primitives_) +
          " primitive(s) not carried (the base shape is read)");
    }
    if (clamped_colors_) {
      out_.notes.push_back(prefix + "COLOR_0 values outside [0, 1] clamped");
    }
    std::string normals;
    std::string others;
    for (const auto& [attribute, count] : dropped_attributes_) {
      std::string& list =
          attribute == "NORMAL" || attribute == "TANGENT" ? normals : others;
      if (!list.empty()) list += ", ";
      list += attribute.substr(0, 40);
    }
    if (!normals.empty()) {
      out_.notes.push_back(prefix + normals +
                           " not carried (recomputed from the surface)");
    }
    if (!others.empty()) {
      out_.notes.push_back(prefix + "vertex attributes " + others +
                           " not carried (one UV set and one colour set are; "
                           "skinning data is not)");
    }
  }

  const tinygltf::Model& model_;
  std::string_view name_;
  const AssetLimits& limits_;
  GltfGeometry out_;
  std::map<std::pair<int, int>, PrimitiveData> cache_;
  std::map<std::string, size_t> dropped_attributes_;
  size_t point_line_primitives_ = 0;
  size_t positionless_primitives_ = 0;
  size_t morphed_primitives_ = 0;
  bool clamped_colors_ = false;
};

}  // namespace

Result<GltfGeometry> BuildGltfGeometry(const tinygltf::Model& model,
                                       std::string_view name,
                                       const AssetLimits& limits) {
  return SceneBuilder(model, name, limits).Build();
}

}  // namespace meshwave
