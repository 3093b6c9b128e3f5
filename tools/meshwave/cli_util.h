// Small helpers shared by the CLI commands: error reporting and JSON output.
#ifndef MESHWAVE_TOOLS_CLI_UTIL_H_
#define MESHWAVE_TOOLS_CLI_UTIL_H_

#include <google/protobuf/message.h>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include "meshwave/encoder.h"
#include "meshwave/mesh.h"
#include "meshwave/progressive_decoder.h"
#include "meshwave/status.h"

namespace meshwave::cli {

// Prints "meshwave <command>: <status>" on stderr and returns exit code 1.
int Fail(const std::string& command, const Status& status);

// Prints a protobuf message as indented JSON on stdout (field names as in
// the .proto, zero values included so the output has a fixed shape).
void PrintJson(const google::protobuf::Message& message);

// Parses a byte count: "65536", "64KiB", "64k", "1.5MB", "2MiB", "1G".
// Decimal (kB, MB) and binary (KiB, MiB, k, M) units.
Result<uint64_t> ParseByteSize(const std::string& text);

// The transform and quantiser options of the commands that encode (encode,
// rd): --predictor/--transform, --update, --levels (remeshing), --precision.
void AddTransformOptions(CLI::App* cmd, std::string& predictor,
                         std::string& update, int& levels, int& precision);
// --sawt-alpha and --sawt-lambda (EncodeOptions::sawt_alpha, sawt_lambda_scale).
void AddSawtOptions(CLI::App* cmd, uint32_t& alpha, double& lambda_scale);
// Applies the parsed values of those options to `options`; an empty
// `update` is the predictor's default (none for sawt, else constant).
Status ApplyTransformOptions(const std::string& predictor,
                             const std::string& update, int precision,
                             EncodeOptions& options);

// --quantizer saq|ueq|z1.5|z2.5|auto: the deadzone of every (subband,
// component), or `auto`, chosen per (subband, component) from the fitted
// Laplacian mixture (Satti et al. 2011).
// --quantizer (the deadzone), --tangent-step (EncodeOptions::tangent_step_scale),
// --base-refinement (EncodeOptions::base_refinement_planes), and the
// precincts: --precinct-size and --split-bytes.
struct QuantizerArgs {
  std::string quantizer = "saq";
  double tangent_step = EncodeOptions{}.tangent_step_scale;
  int base_refinement = EncodeOptions{}.base_refinement_planes;
  uint32_t precinct_size = EncodeOptions{}.precinct_coefficients;
  uint32_t split_bytes = EncodeOptions{}.split_bytes_per_precinct;
};
void AddQuantizerOption(CLI::App* cmd, QuantizerArgs& args);
Status ApplyQuantizerOption(const QuantizerArgs& args, EncodeOptions& options);

// The level of the mesh a command writes: `extra_levels` past the finest
// level that received detail (ProgressiveDecoder::DetailLevels), at most
// max_level (-1: the stream's finest). A level past the details is the
// wavelet's own subdivision with zero details: the first one smooths the
// surface (bunny and horse: +1.3 to +3.4 dB of surface PSNR against the
// original), the next ones add little for four times the faces each
// (about +0.1 dB; docs/RD_RESULTS.md, "Decoded vertex count").
// With the original layer held (DecodeLevel gives its mesh): the finest.
int OutputLevel(const ProgressiveDecoder& decoder, int max_level, int extra_levels);
inline constexpr int kDefaultExtraLevels = 1;

// The mesh a decoder gives at a level, with its vertex colours (linear RGB,
// one per vertex; empty when the stream has no colour channel).
struct DecodedMesh {
  TriMesh mesh;
  // The original layer's mesh (ProgressiveDecoder::OriginalMesh), not a
  // level of the remesh.
  bool original = false;
  std::vector<Vec3> colors;
  // With a texture: each map's finest level held (views into the decoder:
  // valid while it lives and is not reset) and, when any is held, the UVs
  // per face corner; `textured` says whether the stream has a texture.
  bool textured = false;
  std::vector<TextureImage> images;
  std::vector<float> uvs;
  TextureMaterial material;
};
// Packets of the original layer, which closes the index (docs/FORMAT.md
// 2.5): its connectivity, coarse positions and refinement planes.
inline size_t OriginalPackets(const StreamHeader& header) {
  return header.original ? 2 + size_t{header.original->refinement_planes} : 0;
}

// Level `level` of the remesh, or the original mesh when the decoder holds
// enough of its layer and `level` is the finest (or beyond).
DecodedMesh DecodeLevel(const ProgressiveDecoder& decoder, int level);
// Writes it by the path's extension (WriteMesh: the colours go into .ply
// and glTF files; .obj has no place for them; the texture into glTF files
// only, with a warning line for the others): the one writer of `meshwave
// decode`, `fetch` and `refine`.
Status WriteDecodedMesh(const DecodedMesh& decoded, const std::string& path);
inline constexpr const char* kExtraLevelsHelp =
    "Levels subdivided past the finest level that received detail (zero details: "
    "each smooths the surface and quadruples the faces); 12 writes every level up "
    "to --max-level";

// --fidelity DB and --max-vertex-ratio R (meshwave/fidelity.h) on `encode`
// and `remesh`; `what` says what the fidelity is of.
void AddFidelityOptions(CLI::App* cmd, double& fidelity_db, double& max_vertex_ratio,
                        const std::string& what);

// --threads N on the commands that remesh or encode: worker threads, 0 (the
// default) for the machine's cores. Their output does not depend on it.
void AddThreadsOption(CLI::App* cmd, int& threads);
inline constexpr const char* kThreadsHelp =
    "Worker threads for remeshing and encoding (0: the machine's cores); the output "
    "is the same for any number";

// Reads a whole file; IoError naming the path when it cannot.
Result<std::string> ReadFileBytes(const std::string& path);
// Files are written with WriteFileDurably (core/durable_file.h).

}  // namespace meshwave::cli

#endif  // MESHWAVE_TOOLS_CLI_UTIL_H_
