#include "meshwave/asset_encoder.h"

#include <cctype>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "asset/asset_readers.h"
#include "meshwave/attribute_transfer.h"
#include "meshwave/mesh_io.h"
#include "meshwave/texture_bake.h"

namespace meshwave {
namespace {

bool IsGltf(std::string_view name) {
  const size_t dot = name.rfind('.');
  if (dot == std::string_view::npos) return false;
  std::string ext(name.substr(dot));
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".glb" || ext == ".gltf";
}

// The main file's geometry alone, for when the asset reader refuses the
// files: what ReadMesh gives (a .gltf's buffers still come from the set).
Result<TriMesh> GeometryOnly(FileSet& files, std::string_view main_file,
                             const std::string& source_name, const AssetLimits& limits) {
  MW_ASSIGN_OR_RETURN(const MeshFormat format, FormatFromPath(std::string(main_file)));
  MW_ASSIGN_OR_RETURN(const std::string_view bytes, files.Read(main_file));
  if (IsGltf(main_file)) {
    GltfReadOptions geometry;
    geometry.load_images = false;
    MW_ASSIGN_OR_RETURN(MeshAsset asset,
                        ParseGltfAsset(bytes, files, main_file, limits, geometry));
    return std::move(asset.mesh);
  }
  return ParseMesh(bytes, format, source_name);
}

// Whether the textures are baked: some image is used (BakeTexture decides
// which slots) or the materials differ. Their scalars alone (one material,
// no image) are not carried: AttributesLeftOut names them.
bool MayBake(const MeshAsset& asset) { return !asset.images.empty() || asset.materials.size() > 1; }

// Whether a step after remeshing samples the input's surface (so its
// geometry must outlive ToSemiRegular): vertex colours and the bake.
bool NeedsInputSurface(const MeshAsset& asset) { return !asset.color.empty() || MayBake(asset); }

}  // namespace

std::string AttributesLeftOut(std::string_view file, const Result<MeshAsset>& asset) {
  const std::string name(file);
  if (!asset.ok()) {
    return name + ": the stream holds the geometry only; the file's attributes could not "
                  "be read (" + asset.status().ToString() + ")";
  }
  auto count = [](size_t n, const char* one, const char* many) {
    return std::to_string(n) + " " + (n == 1 ? one : many);
  };
  const bool baked = MayBake(*asset);
  std::vector<std::string> parts;
  if (!baked) {
    // No texture to bake: UVs and a lone material's scalars have nothing
    // to travel with.
    if (!asset->uv.empty()) parts.push_back("UVs (no texture uses them)");
    if (!asset->materials.empty()) {
      parts.push_back(count(asset->materials.size(), "material", "materials") +
                      " without a texture");
    }
  }
  if (!asset->notes.empty()) {
    parts.push_back(count(asset->notes.size(), "feature", "features") +
                    " the reader leaves out (meshwave info lists them)");
  }
  if (parts.empty()) return "";
  std::string held = "the geometry";
  if (!asset->color.empty()) held += baked ? ", vertex colours" : " and vertex colours";
  if (baked) held += " and the textures baked onto the remesh";
  std::string line = name + ": the stream holds " + held + "; not coded: ";
  for (size_t i = 0; i < parts.size(); ++i) line += (i == 0 ? "" : ", ") + parts[i];
  return line;
}

Result<AssetEncoding> EncodeAsset(FileSet& files, std::string_view main_file,
                                  const AssetEncodeOptions& options) {
  const std::string source =
      options.source_name.empty() ? std::string(main_file) : options.source_name;
  AssetEncoding out;

  // 1. Read. The asset reader parses the geometry too, so the main file is
  // parsed once; only when it refuses the files is the geometry read alone.
  Result<MeshAsset> read = ParseMeshAsset(files, main_file, options.limits);
  out.read.left_out = AttributesLeftOut(source, read);
  MeshAsset asset;
  if (read.ok()) {
    asset = std::move(read).value();
  } else {
    out.read.attributes_read = false;
    MW_ASSIGN_OR_RETURN(asset.mesh, GeometryOnly(files, main_file, source, options.limits));
    if (!options.geometry_if_attributes_unreadable) {
      // Never a silent loss: the user fixes the files or asks for the
      // geometry alone.
      return Status(read.status().code(),
                    std::string(read.status().message()) +
                        "; nothing encoded (its geometry alone reads: "
                        "--allow-geometry-only encodes it without the attributes)");
    }
  }
  out.read.vertices = asset.mesh.positions.size();
  out.read.faces = asset.mesh.faces.size();
  out.read.colors = !asset.color.empty();
  if (options.on_read) options.on_read(out.read);

  // 2. Geometry: semi-regular as it is, or remeshed.
  if (options.keep_input_mesh) out.input_mesh = asset.mesh;
  const bool original_layer = options.original_layer && asset.color.empty() && !MayBake(asset);
  TriMesh geometry =
      NeedsInputSurface(asset) || original_layer ? asset.mesh : std::move(asset.mesh);
  MW_ASSIGN_OR_RETURN(out.semiregular, ToSemiRegular(std::move(geometry), options.semiregular));
  if (options.on_semiregular) options.on_semiregular(out.semiregular);

  // 3. Attributes sampled from the input's surface onto the finest level.
  MW_ASSIGN_OR_RETURN(VertexAttributes attributes,
                      TransferAttributes(asset, out.semiregular.mesh, options.encode.threads));

  // 4. Textures and materials baked onto the remesh's atlas; vertex
  // colours are baked into the base colour map then, not sent twice.
  if (MayBake(asset)) {
    TextureBakeNotes notes;
    TextureBakeOptions bake = options.bake;
    bake.threads = options.encode.threads;
    Result<std::optional<BakedTexture>> baked =
        BakeTexture(asset, out.semiregular.mesh, bake, &notes);
    MW_RETURN_IF_ERROR(baked.status());
    out.bake_notes = std::move(notes.lines);
    // Moved out of the Result in place (a copy of the optional draws a
    // false -Wmaybe-uninitialized from GCC 12 at -O3).
    if (baked->has_value()) {
      attributes.texture = std::move(**baked);
      attributes.colors.clear();
    }
  }

  // 5. Encode, ending in the original where asked.
  if (original_layer) {
    attributes.original = &asset.mesh;
    if (out.semiregular.remeshed) attributes.original_remesh_psnr_db = out.semiregular.remesh_psnr_db;
  }
  MW_ASSIGN_OR_RETURN(out.stream,
                      EncodeMesh(out.semiregular.mesh, options.encode, attributes));
  out.semiregular.mesh = SemiRegularMesh{};  // the stream's copy is what callers use
  return out;
}

}  // namespace meshwave
