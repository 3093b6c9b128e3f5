// meshwave decode IN.mwv OUT: the mesh a stream (or a part of it) gives.
#include <chrono>
#include <cstdio>
#include <iostream>

#include "cli_util.h"
#include "commands.h"
#include "meshwave.pb.h"
#include "core/durable_file.h"
#include "meshwave/container.h"
#include "meshwave/gltf.h"
#include "meshwave/mesh.h"
#include "meshwave/mesh_io.h"
#include "meshwave/progression.h"
#include "meshwave/progressive_decoder.h"
#include "meshwave/stream_limits.h"

namespace meshwave::cli {
namespace {

struct DecodeArgs {
  std::string in, out, order = "quality", budget;
  int max_level = -1;
  int extra_levels = kDefaultExtraLevels;
  bool json = false;
};

double MillisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

Status Run(const DecodeArgs& args) {
  MW_ASSIGN_OR_RETURN(Progression progression, ParseProgression(args.order));
  uint64_t budget = UINT64_MAX;
  if (!args.budget.empty()) {
    MW_ASSIGN_OR_RETURN(budget, ParseByteSize(args.budget));
  }
  MW_ASSIGN_OR_RETURN(std::string bytes, ReadFileBytes(args.in));
  // Timed from parsing to the reconstructed mesh: what a client spends on
  // bytes already in memory (reading and writing files excluded).
  const auto start = std::chrono::steady_clock::now();
  auto parsed = ParseContainer(bytes, /*allow_truncated=*/true);
  if (!parsed.ok()) return parsed.status().WithContext(args.in);
  if (parsed->missing_bytes > 0) {
    std::cerr << "warning: " << args.in << " is cut short ("
              << parsed->missing_bytes
              << " bytes missing); decoding the complete packets\n";
  }
  auto decoder = ProgressiveDecoder::Create(parsed->header);
  if (!decoder.ok()) return decoder.status().WithContext(args.in);
  const int levels = static_cast<int>(parsed->header.transform.levels);
  const int max_level = args.max_level < 0 ? levels : std::min(args.max_level, levels);

  // Present packets by id; follow the order while packets are present and
  // the budget (container size) allows.
  std::vector<int> slot(parsed->header.packets.length.size(), -1);
  for (size_t i = 0; i < parsed->ids.size(); ++i) slot[parsed->ids[i]] = static_cast<int>(i);
  const auto order = PacketOrder(parsed->header, progression, max_level);
  std::vector<uint32_t> available;
  for (uint32_t id : order) {
    if (slot[id] < 0) break;
    available.push_back(id);
  }
  const Selection selection = SelectPackets(parsed->header, available, budget);
  if (selection.ids.empty() && ContainerSize(parsed->header, {}) > budget) {
    return InvalidArgument("budget " + args.budget + " is smaller than the stream header (" +
                           std::to_string(ContainerSize(parsed->header, {})) + " bytes)");
  }
  for (uint32_t id : selection.ids) {
    MW_RETURN_IF_ERROR((*decoder)->AddPacket(id, parsed->payloads[slot[id]]));
  }
  const int level = OutputLevel(**decoder, max_level, args.extra_levels);
  const DecodedMesh decoded = DecodeLevel(**decoder, level);
  const TriMesh& mesh = decoded.mesh;
  const std::vector<Vec3>& colors = decoded.colors;
  const double decode_ms = MillisecondsSince(start);
  MW_RETURN_IF_ERROR(WriteDecodedMesh(decoded, args.out));
  if (args.json) {
    proto::DecodeReport report;
    report.set_output(args.out);
    report.set_vertices(mesh.positions.size());
    report.set_faces(mesh.faces.size());
    report.set_level(level);
    report.set_levels(levels);
    report.set_order(ProgressionName(progression));
    report.set_packets(selection.ids.size());
    report.set_packets_total(order.size());
    report.set_bytes(selection.bytes);
    report.set_estimated_psnr_db((*decoder)->EstimatedPsnr());
    report.set_decode_ms(decode_ms);
    PrintJson(report);
    return Status::Ok();
  }
  std::string texture;
  for (const TextureImage& image : decoded.images) {
    texture += std::string(texture.empty() ? ", textured: " : ", ") +
               std::string(TextureRoleName(image.role)) + " " + std::to_string(image.width) +
               " x " + std::to_string(image.height);
  }
  // A written vertex per (vertex, UV): the validator counts those.
  const size_t written = decoded.images.empty() || !GltfFormFromPath(args.out)
                             ? mesh.positions.size()
                             : TexturedVertexCount(mesh, decoded.uvs);
  std::printf("wrote %s: %zu vertices, %zu faces (level %d of %d)%s%s\n", args.out.c_str(),
              written, mesh.faces.size(), level, levels,
              colors.empty() ? "" : ", with vertex colours", texture.c_str());
  std::printf("%zu of %zu packets in %s order, %llu bytes, estimated PSNR %.2f dB "
              "(against the encoded mesh)\n",
              selection.ids.size(), order.size(), ProgressionName(progression),
              static_cast<unsigned long long>(selection.bytes),
              (*decoder)->EstimatedPsnr());
  std::printf("decoded in %.2f ms (parsing to mesh; file I/O excluded)\n", decode_ms);
  return Status::Ok();
}

}  // namespace

void AddDecodeCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<DecodeArgs>();
  CLI::App* cmd = app.add_subcommand(
      "decode", "Decode a .mwv stream, whole or truncated to a budget, into a mesh");
  cmd->add_option("in", args->in, "Stream (.mwv)")->required();
  cmd->add_option("out", args->out, "Output mesh (.ply, .obj, .glb or .gltf)")->required();
  cmd->add_option("--budget", args->budget,
                  "Bytes of the stream to use, header included (e.g. 20000, 64KiB)");
  cmd->add_option("--order", args->order, "Packet order: quality, resolution or rd")
      ->check(CLI::IsMember({"quality", "resolution", "rd"}))
      ->capture_default_str();
  cmd->add_option("--max-level", args->max_level,
                  "Stop at this subdivision level (a coarser mesh with fewer vertices)")
      ->check(CLI::Range(0, kMaxStreamLevels));
  cmd->add_option("--extra-levels", args->extra_levels, kExtraLevelsHelp)
      ->check(CLI::Range(0, kMaxStreamLevels))
      ->capture_default_str();
  cmd->add_flag("--json", args->json,
                "Print one JSON object (counts, bytes, estimated PSNR, decode time)");
  cmd->callback([args, &exit_code] {
    const Status s = Run(*args);
    if (!s.ok()) exit_code = Fail("decode", s);
  });
}

}  // namespace meshwave::cli
