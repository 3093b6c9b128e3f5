// MeshAsset: a triangle mesh with what it looks like: texture coordinates,
// vertex colours, materials and their images, read from glTF 2.0 (.glb,
// .gltf), OBJ + MTL, PLY (vertex colours) or OFF. The geometry is a TriMesh
// as ReadMesh gives it (positions welded, so the remesher sees one
// connected surface); attributes are indexed per face corner, OBJ-style, so
// that welding positions loses nothing at UV seams or colour borders.
//
// Readers are safe on untrusted bytes: malformed input, a missing file, an
// index out of range, NaN coordinates, a path leaving the file set or a
// limit exceeded each give a Status naming the file and what is wrong, and
// every count is checked against the bytes that hold it (or a limit) before
// it sizes an allocation. What the data model does not carry is listed in
// MeshAsset::notes, one line each, never dropped silently.
#ifndef MESHWAVE_MESH_ASSET_H_
#define MESHWAVE_MESH_ASSET_H_

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "meshwave/file_set.h"
#include "meshwave/mesh.h"
#include "meshwave/status.h"

namespace meshwave {

// Values of one attribute and, for each face of the mesh, the indices of
// its three corners' values, in the face's corner order. Both empty when
// the asset has no such attribute; otherwise faces.size() equals the mesh's
// face count and every index is below values.size().
template <class T>
struct CornerAttribute {
  std::vector<T> values;
  std::vector<Face> faces;

  bool empty() const { return faces.empty(); }
};

enum class WrapMode : uint8_t { kRepeat, kClampToEdge, kMirroredRepeat };
enum class AlphaMode : uint8_t { kOpaque, kMask, kBlend };

// One texture slot of a material.
struct TextureRef {
  int32_t image = -1;  // index into MeshAsset::images; -1: no texture
  WrapMode wrap_u = WrapMode::kRepeat;
  WrapMode wrap_v = WrapMode::kRepeat;
  // Applied to a corner's UV before sampling: uv' = transform * (u, v, 1).
  // glTF's KHR_texture_transform (offset, rotation, scale), MTL's -o/-s;
  // per slot, since the slots of one material may differ.
  Eigen::Matrix<float, 2, 3> transform = Eigen::Matrix<float, 2, 3>::Identity();

  bool present() const { return image >= 0; }
};

// glTF 2.0 metallic-roughness material; MTL materials are mapped onto it
// (Kd, map_Kd: base colour; map_Bump, bump, norm: normal texture; d, Tr:
// alpha; Ke, map_Ke: emissive; Pr, Pm: roughness, metallic).
struct Material {
  std::string name;
  Eigen::Vector4f base_color_factor{1.0f, 1.0f, 1.0f, 1.0f};  // linear RGBA
  TextureRef base_color_texture;  // sRGB-encoded RGB, linear alpha
  float metallic_factor = 1.0f;
  float roughness_factor = 1.0f;
  TextureRef metallic_roughness_texture;  // G: roughness, B: metallic
  TextureRef normal_texture;              // tangent space
  float normal_scale = 1.0f;
  TextureRef occlusion_texture;  // R
  float occlusion_strength = 1.0f;
  Eigen::Vector3f emissive_factor{0.0f, 0.0f, 0.0f};  // linear RGB
  TextureRef emissive_texture;                        // sRGB-encoded RGB
  AlphaMode alpha_mode = AlphaMode::kOpaque;
  float alpha_cutoff = 0.5f;  // kMask only
  bool double_sided = false;
};

// A texture image: decoded pixels and the original encoded bytes.
struct AssetImage {
  std::string name;       // the file in the set, or "image 3 \"name\""
  std::string mime_type;  // sniffed from the bytes: image/png, jpeg, webp
  std::string encoded;    // the original file or glTF image bytes
  uint32_t width = 0;
  uint32_t height = 0;
  // width * height * 4 bytes, 8-bit RGBA, rows top to bottom. Empty when
  // the image could not be decoded and no carried slot uses it (a note
  // says why).
  std::vector<uint8_t> rgba;
};

struct MeshAsset {
  // Positions welded (exactly equal coordinates merged, the first one kept),
  // in the glTF scene's world space (node transforms applied); faces as
  // read, counter-clockwise, none dropped (degenerate ones included: the
  // pipeline's CleanMesh drops them).
  TriMesh mesh;
  // Texture coordinates in glTF's convention: (0, 0) is the top-left corner
  // of an image, v grows downwards (OBJ's vt are flipped: v = 1 - vt). May
  // leave [0, 1] (wrap modes). Faces of a part without coordinates index a
  // shared (0, 0).
  CornerAttribute<Eigen::Vector2f> uv;
  // Linear RGBA in [0, 1]. glTF COLOR_0 as stored (normalised integers
  // scaled); PLY colours, sRGB-encoded by convention, decoded to linear.
  // Faces of a part without colours index a shared opaque white.
  CornerAttribute<Eigen::Vector4f> color;
  // Index into `materials` per face; empty when the input names no
  // material. Faces without one use a default material (glTF's: white,
  // metallic 1, roughness 1), appended to `materials`.
  std::vector<uint32_t> face_material;
  std::vector<Material> materials;
  std::vector<AssetImage> images;
  // One line per feature of the input the model does not carry (normals,
  // skins, animation, extra UV sets, unsupported extensions, cameras,
  // points and lines, ...), for the user: "ToyCar.gltf: 8 cameras not
  // carried".
  std::vector<std::string> notes;
};

// Bounds on what one asset may take. The defaults admit every real asset
// we know of with room to spare; a server may lower them.
struct AssetLimits {
  // Bytes of all files read (the .gltf/.glb, .bin, .mtl, images).
  uint64_t max_file_bytes = uint64_t{2} << 30;
  // Pixels of one image (an 8192 x 8192 texture), checked from its header
  // before decoding.
  uint64_t max_image_pixels = uint64_t{64} << 20;
  // Decoded RGBA bytes of all images together (four 8192² textures).
  uint64_t max_image_bytes = uint64_t{1} << 30;
  // Triangles of the whole asset, after instancing (a glTF mesh drawn by
  // many nodes counts once per node) and strip/fan conversion; and vertex
  // records read from all primitives (glTF), or v and vt lines (OBJ).
  // 16.7 M each: photogrammetry scans are 1-10 M triangles, and an asset
  // at the limit takes some 2 GB (faces, index triples, values, positions).
  uint64_t max_triangles = uint64_t{1} << 24;
  uint64_t max_vertices = uint64_t{1} << 24;
  // Depth of the glTF node tree.
  uint32_t max_node_depth = 64;
  // Bytes of glTF JSON (the .gltf file or the GLB JSON chunk: data URIs
  // make it large), its values (numbers, strings, arrays, objects: each
  // costs some 50 bytes in each of the two parsed copies) and its nesting
  // depth.
  uint64_t max_json_bytes = uint64_t{256} << 20;
  uint64_t max_json_values = uint64_t{1} << 23;
  uint32_t max_json_depth = 64;
};

// Reads the asset whose main file is `main_file` in `files`: .glb, .gltf,
// .obj, .ply or .off by the name's extension (any case). Files it refers to
// (.bin, images, .mtl) are read from `files`, relative to main_file's folder.
// kInvalidArgument for an unknown extension; ParseError, kNotFound,
// kUnsupported as the readers find; never a partial asset.
Result<MeshAsset> ParseMeshAsset(FileSet& files, std::string_view main_file,
                                 const AssetLimits& limits = {});

// ParseMeshAsset on a DirectoryFileSet of the file's folder.
Result<MeshAsset> ReadMeshAsset(const std::filesystem::path& path,
                                const AssetLimits& limits = {});

// A paragraph for people: UVs and colours present or not, materials with
// their textures, images with their sizes, then the notes.
std::string DescribeMeshAsset(const MeshAsset& asset);

}  // namespace meshwave

#endif  // MESHWAVE_MESH_ASSET_H_
