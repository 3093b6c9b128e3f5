// meshwave decode IN.mwv OUT: the mesh a stream (or a part of it) gives.
#include <cstdio>
#include <iostream>

#include "cli_util.h"
#include "commands.h"
#include "meshwave/container.h"
#include "meshwave/mesh.h"
#include "meshwave/progression.h"
#include "meshwave/progressive_decoder.h"

namespace meshwave::cli {
namespace {

struct DecodeArgs {
  std::string in, out, order = "quality", budget;
  int max_level = -1;
};

Status Run(const DecodeArgs& args) {
  MW_ASSIGN_OR_RETURN(Progression progression, ParseProgression(args.order));
  uint64_t budget = UINT64_MAX;
  if (!args.budget.empty()) {
    MW_ASSIGN_OR_RETURN(budget, ParseByteSize(args.budget));
  }
  MW_ASSIGN_OR_RETURN(std::string bytes, ReadFileBytes(args.in));
  auto parsed = ParseContainer(bytes, /*allow_truncated=*/true);
  if (!parsed.ok()) return parsed.status().WithContext(args.in);
  if (parsed->missing_bytes > 0) {
    std::cerr << "warning: " << args.in << " is cut short ("
              << parsed->missing_bytes
              << " bytes missing); decoding the complete packets\n";
  }
  auto decoder = ProgressiveDecoder::Create(parsed->header);
  if (!decoder.ok()) return decoder.status().WithContext(args.in);
  const int levels = static_cast<int>(parsed->header.transform().levels());
  const int max_level = args.max_level < 0 ? levels : std::min(args.max_level, levels);

  // Present packets by id; follow the order while packets are present and
  // the budget (container size) allows.
  std::vector<int> slot(parsed->header.packets().length_size(), -1);
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
  const TriMesh mesh = (*decoder)->Mesh(max_level);
  MW_RETURN_IF_ERROR(WriteMesh(mesh, args.out));
  std::printf("wrote %s: %zu vertices, %zu faces (level %d of %d)\n", args.out.c_str(),
              mesh.positions.size(), mesh.faces.size(), max_level, levels);
  std::printf("%zu of %zu packets in %s order, %llu bytes, estimated PSNR %.2f dB\n",
              selection.ids.size(), order.size(), ProgressionName(progression),
              static_cast<unsigned long long>(selection.bytes),
              (*decoder)->EstimatedPsnr());
  return Status::Ok();
}

}  // namespace

void AddDecodeCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<DecodeArgs>();
  CLI::App* cmd = app.add_subcommand(
      "decode", "Decode a .mwv stream, whole or truncated to a budget, into a mesh");
  cmd->add_option("in", args->in, "Stream (.mwv)")->required();
  cmd->add_option("out", args->out, "Output mesh (.ply or .obj)")->required();
  cmd->add_option("--budget", args->budget,
                  "Bytes of the stream to use, header included (e.g. 20000, 64KiB)");
  cmd->add_option("--order", args->order, "Packet order: quality, resolution or rd")
      ->check(CLI::IsMember({"quality", "resolution", "rd"}))
      ->capture_default_str();
  cmd->add_option("--max-level", args->max_level,
                  "Stop at this subdivision level (a coarser mesh with fewer vertices)")
      ->check(CLI::Range(0, 12));
  cmd->callback([args, &exit_code] {
    const Status s = Run(*args);
    if (!s.ok()) exit_code = Fail("decode", s);
  });
}

}  // namespace meshwave::cli
