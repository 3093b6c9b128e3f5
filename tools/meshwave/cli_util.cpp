#include "cli_util.h"

#include <google/protobuf/util/json_util.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <optional>
#include <iostream>
#include <sstream>

#include "core/parallel_for.h"
#include "core/durable_file.h"
#include "meshwave/gltf.h"
#include "meshwave/mesh_io.h"

namespace meshwave::cli {

int Fail(const std::string& command, const Status& status) {
  std::cerr << "meshwave " << command << ": " << status.ToString() << "\n";
  return 1;
}

void PrintJson(const google::protobuf::Message& message) {
  google::protobuf::util::JsonPrintOptions options;
  options.add_whitespace = true;
  options.always_print_primitive_fields = true;
  options.preserve_proto_field_names = true;
  std::string out;
  auto status = google::protobuf::util::MessageToJsonString(message, &out, options);
  if (!status.ok()) {
    std::cerr << "meshwave: cannot print JSON: " << status.ToString() << "\n";
    return;
  }
  std::cout << out;
}

Result<uint64_t> ParseByteSize(const std::string& text) {
  size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    return InvalidArgument("not a byte count: \"" + text + "\"");
  }
  std::string unit = text.substr(used);
  for (char& c : unit) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  double scale = 1;
  if (unit.empty() || unit == "b") {
    scale = 1;
  } else if (unit == "k" || unit == "kib") {
    scale = 1024;
  } else if (unit == "kb") {
    scale = 1000;
  } else if (unit == "m" || unit == "mib") {
    scale = 1024.0 * 1024;
  } else if (unit == "mb") {
    scale = 1e6;
  } else if (unit == "g" || unit == "gib") {
    scale = 1024.0 * 1024 * 1024;
  } else if (unit == "gb") {
    scale = 1e9;
  } else {
    return InvalidArgument("unknown unit in byte count \"" + text +
                           "\" (use B, kB, KiB, MB, MiB, GB, GiB)");
  }
  const double bytes = value * scale;
  if (!(bytes >= 0) || bytes > 1e18) {
    return InvalidArgument("byte count out of range: \"" + text + "\"");
  }
  return static_cast<uint64_t>(bytes);
}

void AddTransformOptions(CLI::App* cmd, std::string& predictor,
                         std::string& update, int& levels, int& precision) {
  cmd->add_option("--predictor,--transform", predictor,
                  "Wavelet prediction: butterfly, linear, loop, or sawt (spatially "
                  "adaptive, Denis et al. 2010a: one of six filters per octree region and level, "
                  "the choices coded in the header)")
      ->check(CLI::IsMember({"butterfly", "linear", "loop", "sawt"}))
      ->capture_default_str();
  cmd->add_option("--update", update,
                  "Lifting update: constant (lifted), none (unlifted) or valence "
                  "(default: constant; none with sawt)")
      ->check(CLI::IsMember({"constant", "none", "valence", "lifted", "unlifted"}));
  cmd->add_option("--levels", levels,
                  "Subdivision levels when remeshing (default: chosen from the input)")
      ->check(CLI::Range(1, 8));
  cmd->add_option("--precision", precision,
                  "Finest step = bounding-box diagonal x 2^-precision")
      ->check(CLI::Range(4, 30))
      ->capture_default_str();
}

void AddSawtOptions(CLI::App* cmd, uint32_t& alpha, double& lambda_scale) {
  cmd->add_option("--sawt-alpha", alpha,
                  "SAWT: split octree cells while they hold at least this many vertices")
      ->check(CLI::Range(1u, 1u << 30))
      ->capture_default_str();
  cmd->add_option("--sawt-lambda", lambda_scale,
                  "SAWT: Lagrangian weight of the filter index bits, in units of the "
                  "finest step squared")
      ->check(CLI::Range(0.0, 1e12))
      ->capture_default_str();
}

Status ApplyTransformOptions(const std::string& predictor,
                             const std::string& update, int precision,
                             EncodeOptions& options) {
  MW_ASSIGN_OR_RETURN(options.transform.predictor, ParsePredictor(predictor));
  if (update.empty()) {
    // SAWT chooses its filters on prediction error alone: unlifted by
    // default (docs/CODEC.md, "SAWT"); every other predictor is lifted.
    options.transform.update = options.transform.predictor == Predictor::kSawt
                                   ? UpdateWeights::kNone
                                   : UpdateWeights::kConstant;
  } else {
    MW_ASSIGN_OR_RETURN(options.transform.update, ParseUpdateWeights(update));
  }
  options.precision = precision;
  return Status::Ok();
}

void AddQuantizerOption(CLI::App* cmd, QuantizerArgs& args) {
  cmd->add_option("--quantizer", args.quantizer,
                  "Deadzone: saq (z = 2), ueq (z = 1), z1.5, z2.5, or auto (per subband "
                  "and component from the fitted Laplacian mixture, Satti et al. 2011)")
      ->check(CLI::IsMember({"saq", "ueq", "z1.5", "z2.5", "auto"}))
      ->capture_default_str();
  cmd->add_option("--tangent-step", args.tangent_step,
                  "Step of the two tangential detail components over the normal one's "
                  "(local frames): sliding along the surface barely changes it; 1 "
                  "quantises all three alike")
      ->check(CLI::Range(1.0, 1024.0))
      ->capture_default_str();
  cmd->add_option("--base-refinement", args.base_refinement,
                  "The base mesh's positions travel in the header this many bits per "
                  "coordinate coarser, and as many packets refine them, so that a small "
                  "budget does not pay for their low bits; -1: as many as cost the whole "
                  "stream nothing (at most 2 % more base bytes); 0: the whole base in the "
                  "header")
      ->check(CLI::Range(-1, 20))
      ->capture_default_str();
  cmd->add_option("--precinct-size", args.precinct_size,
                  "Precincts, so that a region can be streamed first: base faces grouped "
                  "into runs of at least this many coefficients per subband, each coded on "
                  "its own; 0: none (a region request then gets the uniform order)")
      ->check(CLI::Range(0u, 1u << 30))
      ->capture_default_str();
  cmd->add_option("--split-bytes", args.split_bytes,
                  "A packet is split into one codeword per precinct where its precincts "
                  "would average at least this many bytes")
      ->check(CLI::Range(1u, 1u << 20))
      ->capture_default_str();
}

Status ApplyQuantizerOption(const QuantizerArgs& args, EncodeOptions& options) {
  options.tangent_step_scale = args.tangent_step;
  options.base_refinement_planes = args.base_refinement;
  options.precinct_coefficients = args.precinct_size;
  options.split_bytes_per_precinct = args.split_bytes;
  const std::string& quantizer = args.quantizer;
  // Codes of quant/deadzone_quantizer.h.
  if (quantizer == "saq") options.deadzone = 0;
  else if (quantizer == "ueq") options.deadzone = 1;
  else if (quantizer == "z1.5") options.deadzone = 2;
  else if (quantizer == "z2.5") options.deadzone = 3;
  else if (quantizer == "auto") options.auto_deadzone = true;
  else return InvalidArgument("unknown quantizer \"" + quantizer + "\"");
  return Status::Ok();
}

Result<std::string> ReadFileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Status(StatusCode::kNotFound, path + ": cannot open");
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) return IoError(path + ": read failed");
  return ss.str();
}

int OutputLevel(const ProgressiveDecoder& decoder, int max_level, int extra_levels) {
  const int levels = static_cast<int>(decoder.header().transform.levels);
  const int cap = (max_level < 0 || max_level > levels) ? levels : max_level;
  // The original mesh stands above every level (DecodeLevel).
  if (decoder.OriginalReady() && cap == levels) return levels;
  return std::min(cap, decoder.DetailLevels() + std::max(extra_levels, 0));
}

DecodedMesh DecodeLevel(const ProgressiveDecoder& decoder, int level) {
  DecodedMesh out;
  // The user's own mesh once its layer gives it, unless a coarser level is
  // asked for (docs/FORMAT.md 2.5).
  const int levels = static_cast<int>(decoder.header().transform.levels);
  if (decoder.OriginalReady() && (level < 0 || level >= levels)) {
    out.mesh = decoder.OriginalMesh();
    out.original = true;
    return out;
  }
  out.mesh = decoder.Mesh(level);
  out.colors = decoder.Colors(level);
  out.textured = decoder.HasTexture();
  if (out.textured) {
    // Every vertex's UV comes from the atlas; with no level held yet the
    // mesh is written alone.
    for (size_t m = 0; m < decoder.texture().maps.size(); ++m) {
      if (auto image = decoder.BestTextureLevel(m)) out.images.push_back(*std::move(image));
    }
    if (!out.images.empty()) out.uvs = decoder.TextureCoordinates(level);
    out.material = decoder.texture().material;
  }
  return out;
}

Status WriteDecodedMesh(const DecodedMesh& decoded, const std::string& path) {
  const std::optional<GltfForm> gltf = GltfFormFromPath(path);
  if (!decoded.images.empty() && gltf) {
    return WriteFileDurably(path, SerializeTexturedGltf(decoded.mesh, *gltf, decoded.uvs,
                                                        decoded.images, decoded.material,
                                                        decoded.colors));
  }
  if (decoded.textured && !gltf) {
    std::cerr << "warning: " << path
              << ": the stream's texture is not written (only .glb and .gltf outputs carry it)\n";
  }
  return WriteMesh(decoded.mesh, path, decoded.colors);
}

void AddFidelityOptions(CLI::App* cmd, double& fidelity_db, double& max_vertex_ratio,
                        const std::string& what) {
  cmd->add_option("--fidelity", fidelity_db,
                  "Symmetric surface PSNR (dB, peak = the input's bounding-box diagonal) " + what +
                      " should reach against the input: remeshed denser until it does; prints "
                      "what it reached. The default is about what Draco's default quantisation "
                      "gives; 0 remeshes once at about the input's density")
      ->check(CLI::Range(0.0, 200.0))
      ->capture_default_str();
  cmd->add_option("--max-vertex-ratio", max_vertex_ratio,
                  "The densest remesh --fidelity may make, in finest vertices per input vertex")
      ->check(CLI::Range(1.0, 64.0))
      ->capture_default_str();
}

void AddThreadsOption(CLI::App* cmd, int& threads) {
  cmd->add_option("--threads", threads, kThreadsHelp)
      ->check(CLI::Range(0, kMaxParallelThreads))
      ->capture_default_str();
}

}  // namespace meshwave::cli
