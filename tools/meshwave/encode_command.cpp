// meshwave encode IN OUT.mwv: a mesh file into an embedded 3xC stream.
// Semi-regular input is used as it is; irregular input is remeshed first.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "cli_util.h"
#include "commands.h"
#include "core/durable_file.h"
#include "meshwave/asset_encoder.h"
#include "meshwave/container.h"
#include "meshwave/encoder.h"
#include "meshwave/fidelity.h"
#include "meshwave/file_set.h"
#include "meshwave/mesh.h"
#include "meshwave/semiregular.h"
#include "meshwave/semiregular_input.h"
#include "meshwave/texture.h"
#include "stream.pb.h"

namespace meshwave::cli {
namespace {

struct EncodeArgs {
  std::string in, out, predictor = "butterfly", update = "",
                        coder = "3xc";
  QuantizerArgs quantizer;
  int levels = -1;
  int precision = 16;
  bool precision_given = false;
  double fidelity_db = kDefaultFidelityDb;
  double max_vertex_ratio = kDefaultMaxVertexRatio;
  bool force_remesh = false;
  uint32_t sawt_alpha = EncodeOptions{}.sawt_alpha;
  double sawt_lambda = EncodeOptions{}.sawt_lambda_scale;
  float texture_weight = EncodeOptions{}.texture_rd_weight;
  bool allow_geometry_only = false;
  bool original_layer = true;
  int threads = 0;
  TextureBakeOptions bake;
};

// The first texture packet's id: texture packets come before the original
// layer's.
size_t TexturePacketsStart(const StreamHeader& header) {
  size_t first = header.packets.length.size() - OriginalPackets(header);
  if (!header.texture) return first;
  for (const StreamHeader::Texture::Map& map : header.texture->maps) {
    for (const StreamHeader::Texture::Level& level : map.levels) {
      first = std::min<size_t>(first, level.packet);
    }
  }
  return first;
}

// "texture: atlas 1024 x 1024 (cells of 64 texels); base colour image/jpeg
// 3 levels 98,304 bytes, ...": what the bake made.
void PrintTexture(const EncodedStream& stream) {
  const StreamHeader::Texture& texture = *stream.header.texture;
  const auto& finest = texture.maps.front().levels.back();
  std::printf("texture: atlas %u x %u (cells of %u texels, gutter %u)", finest.width,
              finest.height, texture.cell, texture.gutter);
  for (const StreamHeader::Texture::Map& map : texture.maps) {
    uint64_t bytes = 0;
    for (const StreamHeader::Texture::Level& level : map.levels) {
      bytes += stream.packets[level.packet].size();
    }
    std::printf("; %s %s, %zu levels, %llu bytes",
                std::string(TextureRoleName(static_cast<TextureRole>(map.role))).c_str(),
                map.mime_type.c_str(), map.levels.size(), static_cast<unsigned long long>(bytes));
  }
  std::printf("\n");
}

SemiRegularInputOptions SemiRegularOptions(const EncodeArgs& args) {
  SemiRegularInputOptions options;
  options.force_remesh = args.force_remesh;
  options.levels = args.levels;
  options.fidelity_db = args.fidelity_db;
  options.max_vertex_ratio = args.max_vertex_ratio;
  options.threads = args.threads;
  return options;
}

// What ToSemiRegular did, as the pipeline reaches it.
void ReportSemiRegular(const EncodeArgs& args, const SemiRegularInput& input) {
  if (!input.remeshed) {
    std::cerr << args.in << ": semi-regular, " << input.levels
              << " levels over " << input.base_faces << " base faces\n";
    return;
  }
  if (!args.force_remesh) {
    std::cerr << args.in << ": not semi-regular ("
              << input.not_semiregular_reason << "); remeshing first\n";
  }
  for (const auto& w : input.warnings) std::cerr << "warning: " << w << "\n";
  std::cerr << "remeshed: " << input.levels << " levels over "
            << input.base_faces << " base faces, " << input.finest_vertices
            << " vertices\n";
  if (args.fidelity_db > 0) {
    std::fprintf(stderr, "remesh: %.2f dB surface PSNR against the input after %d attempt%s\n",
                 input.remesh_psnr_db, input.remesh_attempts,
                 input.remesh_attempts == 1 ? "" : "s");
  }
}

// What --fidelity reached: the complete stream against the file as read.
Status ReportFidelity(const EncodeArgs& args, const TriMesh& original,
                      const SemiRegularInput& input, const EncodedStream& stream,
                      int precision) {
  MW_ASSIGN_OR_RETURN(const double psnr, CompleteStreamPsnr(original, stream, args.threads));
  std::printf("fidelity: the complete stream is at %.2f dB of symmetric surface PSNR "
              "against %s (asked %.2f dB; precision %d)\n",
              psnr, args.in.c_str(), args.fidelity_db, precision);
  if (psnr >= args.fidelity_db) return Status::Ok();
  const double ratio = static_cast<double>(input.finest_vertices) /
                       static_cast<double>(std::max<size_t>(original.positions.size(), 1));
  std::string why;
  if (!input.remeshed) {
    why = "the input is used as it is (semi-regular): --remesh lets it be remeshed denser";
  } else if (ratio >= 0.95 * args.max_vertex_ratio) {
    char limit[160];
    std::snprintf(limit, sizeof limit,
                  "the remesh reached the density limit (%zu vertices, --max-vertex-ratio %g)",
                  input.finest_vertices, args.max_vertex_ratio);
    why = limit;
  } else {
    why = "a denser remesh did not get closer";
  }
  std::fprintf(stderr, "warning: fidelity %.2f dB not reached: %s\n", args.fidelity_db,
               why.c_str());
  return Status::Ok();
}

Status Run(const EncodeArgs& args) {
  EncodeOptions options;
  const int precision = args.fidelity_db > 0 && !args.precision_given
                            ? PrecisionForFidelity(args.fidelity_db)
                            : args.precision;
  MW_RETURN_IF_ERROR(ApplyTransformOptions(args.predictor, args.update, precision, options));
  options.sawt_alpha = args.sawt_alpha;
  options.sawt_lambda_scale = args.sawt_lambda;
  options.texture_rd_weight = args.texture_weight;
  MW_ASSIGN_OR_RETURN(options.coder, ParseCoderKind(args.coder));
  MW_RETURN_IF_ERROR(ApplyQuantizerOption(args.quantizer, options));
  options.name = std::filesystem::path(args.in).stem().string();
  options.threads = args.threads;
  AssetEncodeOptions pipeline;
  pipeline.encode = options;
  pipeline.bake = args.bake;
  pipeline.semiregular = SemiRegularOptions(args);
  pipeline.source_name = args.in;
  pipeline.keep_input_mesh = args.fidelity_db > 0;  // ReportFidelity measures against it
  pipeline.geometry_if_attributes_unreadable = args.allow_geometry_only;
  pipeline.original_layer = args.original_layer;
  pipeline.on_read = [](const AssetRead& read) {
    if (!read.left_out.empty()) std::cerr << "warning: " << read.left_out << "\n";
  };
  pipeline.on_semiregular = [&args](const SemiRegularInput& input) {
    ReportSemiRegular(args, input);
  };
  const std::filesystem::path in(args.in);
  DirectoryFileSet files(in.has_parent_path() ? in.parent_path() : std::filesystem::path("."),
                         pipeline.limits.max_file_bytes);
  MW_ASSIGN_OR_RETURN(AssetEncoding encoded,
                      EncodeAsset(files, in.filename().string(), pipeline));
  const EncodedStream& stream = encoded.stream;
  const std::string bytes = SerializeFullContainer(stream);
  MW_RETURN_IF_ERROR(WriteFileDurably(args.out, bytes));
  uint64_t payload = 0;
  for (const auto& p : stream.packets) payload += p.size();
  const double v = static_cast<double>(stream.header.vertices);
  const uint32_t planes = stream.header.base.refinement_planes;
  std::printf("wrote %s: %zu bytes (header %zu incl. base mesh %zu, %zu packets %llu "
              "incl. %u base refinement planes of %zu)\n",
              args.out.c_str(), bytes.size(), bytes.size() - payload,
              stream.header.base.coded.size(), stream.packets.size(),
              static_cast<unsigned long long>(payload), planes,
              planes == 0 ? size_t{0} : (3 * size_t{stream.header.base.vertex_count} + 7) / 8);
  std::printf("%llu vertices, %u levels, %s/%s %s: %.3f bits per vertex in all\n",
              static_cast<unsigned long long>(stream.header.vertices),
              stream.header.transform.levels,
              PredictorName(options.transform.predictor),
              UpdateWeightsName(options.transform.update),
              CoderKindName(options.coder), 8.0 * static_cast<double>(bytes.size()) / v);
  if (!stream.header.channels.empty()) {
    // A channel's packets come last: per subband, its top bitplane + 1.
    size_t channel_packets = 0;
    for (const StreamHeader::Channel& channel : stream.header.channels) {
      for (uint32_t j = 0; j < stream.header.transform.levels; ++j) {
        int top = -1;
        for (int c = 0; c < 3; ++c) top = std::max(top, channel.quantizer(static_cast<int>(j), c).top_bitplane);
        channel_packets += static_cast<size_t>(top + 1);
      }
    }
    // ... and before the texture's (docs/FORMAT.md 2.4).
    const size_t texture_packets =
        stream.packets.size() - OriginalPackets(stream.header) - TexturePacketsStart(stream.header);
    const size_t geometry_packets = stream.packets.size() - texture_packets - channel_packets;
    uint64_t channel_bytes = 0;
    for (size_t id = geometry_packets; id < geometry_packets + channel_packets; ++id) {
      channel_bytes += stream.packets[id].size();
    }
    std::printf("colour channel: %zu packets, %llu bytes (precision %d)\n", channel_packets,
                static_cast<unsigned long long>(channel_bytes), options.color_precision);
  }
  if (stream.header.texture) PrintTexture(stream);
  if (const auto& original = stream.header.original) {
    const size_t first = stream.packets.size() - OriginalPackets(stream.header);
    uint64_t positions = 0;
    for (size_t id = first + 1; id < stream.packets.size(); ++id) positions += stream.packets[id].size();
    const double n = std::max<double>(original->vertex_count, 1);
    std::printf("original layer: %u vertices, %llu faces; connectivity %zu bytes (%.2f bits per "
                "vertex), positions %llu bytes (%.2f bits per vertex) in %u + 1 packets "
                "(precision %d)\n",
                original->vertex_count, static_cast<unsigned long long>(original->face_count),
                stream.packets[first].size(), 8.0 * static_cast<double>(stream.packets[first].size()) / n,
                static_cast<unsigned long long>(positions), 8.0 * static_cast<double>(positions) / n,
                original->refinement_planes, options.precision);
  } else if (args.original_layer) {
    std::printf("original layer: left out (the mesh's colours or texture travel on the remesh "
                "only)\n");
  }
  for (const std::string& note : encoded.bake_notes) std::cerr << "warning: " << note << "\n";
  if (!stream.sawt_filter_usage.empty()) {
    // The field as the header carries it: tag, length and message.
    const StreamHeader::SawtChoices& sawt = *stream.header.transform.sawt;
    proto::SawtChoices message;
    message.set_alpha(sawt.alpha);
    message.set_region_count(sawt.region_count);
    message.set_coded(sawt.coded);
    message.set_crc32c(sawt.crc32c);
    const size_t field = message.ByteSizeLong();
    std::printf("sawt: %u regions (alpha %u), header field %zu bytes; choices per filter",
                stream.sawt_regions, options.sawt_alpha, field + 1 + (field < 128 ? 1 : 2));
    for (size_t l = 0; l < stream.sawt_filter_usage.size(); ++l) {
      std::printf(" f%zu:%u", l + 1, stream.sawt_filter_usage[l]);
    }
    std::printf("\n");
  }
  if (args.fidelity_db > 0) {
    MW_RETURN_IF_ERROR(
        ReportFidelity(args, encoded.input_mesh, encoded.semiregular, stream, precision));
  }
  return Status::Ok();
}

}  // namespace

void AddEncodeCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<EncodeArgs>();
  CLI::App* cmd = app.add_subcommand(
      "encode", "Encode a mesh into an embedded .mwv stream (irregular meshes "
                "are remeshed first)");
  cmd->add_option("in", args->in, "Mesh file (.ply, .obj, .off, .glb, .gltf)")->required();
  cmd->add_option("out", args->out, "Output stream (.mwv)")->required();
  AddTransformOptions(cmd, args->predictor, args->update, args->levels,
                      args->precision);
  AddSawtOptions(cmd, args->sawt_alpha, args->sawt_lambda);
  cmd->add_option("--coder", args->coder, "Bitplane coder: 3xc or sim")
      ->check(CLI::IsMember({"3xc", "sim"}))
      ->capture_default_str();
  AddQuantizerOption(cmd, args->quantizer);
  cmd->add_flag("--remesh", args->force_remesh,
                "Remesh even when the input is already semi-regular");
  AddFidelityOptions(cmd, args->fidelity_db, args->max_vertex_ratio,
                     "the complete stream (the precision follows it too)");
  AddThreadsOption(cmd, args->threads);
  cmd->add_option("--texture-max-side", args->bake.max_side,
                  "Textured inputs: the baked atlas's texels a side at most (its size follows "
                  "the input's texel density)")
      ->check(CLI::Range(64, 16384))
      ->capture_default_str();
  cmd->add_option("--texture-quality", args->bake.quality,
                  "Textured inputs: quality of the baked colour maps (WebP) and the "
                  "metallic-roughness map (JPEG); normal maps are lossless PNG")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  cmd->add_flag("!--no-original", args->original_layer,
                "Leave out the final layer that restores the input's own connectivity, vertex "
                "order and positions at --precision (docs/FORMAT.md 2.5): the stream ends in "
                "the remesh");
  cmd->add_flag("--allow-geometry-only", args->allow_geometry_only,
                "When the file's textures or attributes cannot be read (a missing image, a bad "
                "UV index, ...) but its geometry can: encode the geometry alone, with a "
                "warning, instead of failing");
  cmd->add_option("--texture-weight", args->texture_weight,
                  "Textured inputs: the texture's distortion against the geometry's when the "
                  "quality order places the texture levels (docs/FORMAT.md 7)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->callback([args, cmd, &exit_code] {
    args->precision_given = cmd->count("--precision") > 0;
    const Status s = Run(*args);
    if (!s.ok()) exit_code = Fail("encode", s);
  });
}

}  // namespace meshwave::cli
