// From an asset's files to a stream: the one pipeline `meshwave encode`
// and the server's ingest share. The asset is read (ParseMeshAsset), its
// geometry made semi-regular (ToSemiRegular: remeshed when it is not),
// its attributes sampled onto that mesh (TransferAttributes), its textures
// baked onto the remesh's atlas (BakeTexture) and all of it encoded
// (EncodeMesh). What the stream cannot carry yet is said in one
// line, never dropped silently.
#ifndef MESHWAVE_ASSET_ENCODER_H_
#define MESHWAVE_ASSET_ENCODER_H_

#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "meshwave/encoder.h"
#include "meshwave/file_set.h"
#include "meshwave/mesh.h"
#include "meshwave/mesh_asset.h"
#include "meshwave/semiregular_input.h"
#include "meshwave/status.h"
#include "meshwave/texture_bake.h"

namespace meshwave {

// The asset as read, before remeshing: what a caller may log.
struct AssetRead {
  // False: the asset reader refused the files (a missing .mtl or texture,
  // an image over the limits, ...) and the geometry alone was read from
  // the main file; `left_out` says why.
  bool attributes_read = true;
  size_t vertices = 0;
  size_t faces = 0;
  bool colors = false;  // the asset has vertex colours (the stream carries them)
  // "FILE: the stream holds the geometry and vertex colours; not coded:
  // UVs (no texture uses them), 1 material without a texture": what the
  // input holds that the stream does not. Empty when it holds nothing more.
  std::string left_out;
};

struct AssetEncodeOptions {
  AssetLimits limits;
  SemiRegularInputOptions semiregular;
  // name, transform, precision, threads, ...: as EncodeMesh takes them.
  EncodeOptions encode;
  // The texture bake's atlas and pyramid (its threads are encode.threads).
  TextureBakeOptions bake;
  // The file as the user named it ("data/cow.obj"), for messages; empty:
  // the main file's name in the set.
  std::string source_name;
  // When the asset's attributes cannot be read (a missing or undecodable
  // image, a UV index out of range, an image over the pixel limits) but its
  // geometry can: encode the geometry alone and say so in
  // AssetRead::left_out. Off (the default): the reader's error, and
  // nothing is encoded.
  bool geometry_if_attributes_unreadable = false;
  // End the stream in the mesh as read: its connectivity over its own
  // vertex ids and its positions at encode.precision (format version 10,
  // docs/FORMAT.md 2.5). Meshes with vertex colours or a texture leave it
  // out: their attributes travel on the remesh only.
  bool original_layer = true;
  // Keep the geometry as read (AssetEncoding::input_mesh), e.g. to measure
  // the complete stream against it (CompleteStreamPsnr).
  bool keep_input_mesh = false;
  // Called once the asset is read and once the mesh is semi-regular, so a
  // caller can report (and time) each step as it ends.
  std::function<void(const AssetRead&)> on_read;
  std::function<void(const SemiRegularInput&)> on_semiregular;
};

struct AssetEncoding {
  EncodedStream stream;
  AssetRead read;
  // What ToSemiRegular did (remeshed or not, levels, warnings, PSNR); its
  // mesh is released once encoded (the stream's is the encoder's copy).
  SemiRegularInput semiregular;
  TriMesh input_mesh;  // with keep_input_mesh; empty otherwise
  // What the texture bake could not carry, one line each (material
  // extensions, several materials merged, ...): for the log.
  std::vector<std::string> bake_notes;
};

// Encodes the asset whose main file is `main_file` in `files` (.glb,
// .gltf, .obj, .ply, .off by its extension). Safe on untrusted files:
// errors are the readers' (kParseError, kNotFound, kInvalidArgument,
// kUnsupported naming the file), ToSemiRegular's and EncodeMesh's. When
// the asset reader fails but the main file's geometry reads, the error
// says that the geometry alone could be encoded; with
// geometry_if_attributes_unreadable it is, and AssetRead says so.
Result<AssetEncoding> EncodeAsset(FileSet& files, std::string_view main_file,
                                  const AssetEncodeOptions& options);

// The AssetRead::left_out line of `asset`, read from `file` (or of the
// error that kept it from being read).
std::string AttributesLeftOut(std::string_view file, const Result<MeshAsset>& asset);

}  // namespace meshwave

#endif  // MESHWAVE_ASSET_ENCODER_H_
