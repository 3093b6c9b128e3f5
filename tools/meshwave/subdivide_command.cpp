// meshwave subdivide IN OUT --levels N --scheme midpoint|loop|butterfly
#include <spdlog/spdlog.h>

#include <iostream>

#include "cli_util.h"
#include "commands.h"
#include "meshwave/mesh.h"
#include "meshwave/mesh_clean.h"
#include "meshwave/mesh_io.h"
#include "meshwave/semiregular.h"
#include "meshwave/stream_limits.h"
#include "meshwave/subdivision.h"

namespace meshwave::cli {
namespace {

struct SubdivideArgs {
  std::string in, out, scheme = "butterfly";
  int levels = 3;
  bool clean = true;
};

Status Run(const SubdivideArgs& args) {
  MW_ASSIGN_OR_RETURN(SubdivisionScheme scheme,
                      ParseSubdivisionScheme(args.scheme));
  MW_ASSIGN_OR_RETURN(TriMesh base, ReadMesh(args.in));
  if (args.clean) {
    const CleanReport r = CleanMesh(base);
    if (r.merged_vertices + r.degenerate_faces + r.duplicate_faces +
            r.unreferenced_vertices > 0) {
      spdlog::info("cleaned {}: {} vertices merged, {} degenerate and {} "
                   "duplicate faces dropped, {} unreferenced vertices dropped",
                   args.in, r.merged_vertices, r.degenerate_faces,
                   r.duplicate_faces, r.unreferenced_vertices);
    }
  }
  auto sr = Subdivide(base, args.levels, scheme);
  if (!sr.ok()) return sr.status().WithContext(args.in);
  const TriMesh out = sr->Finest();
  MW_RETURN_IF_ERROR(WriteMesh(out, args.out));
  std::cerr << "wrote " << args.out << ": " << out.positions.size()
            << " vertices, " << out.faces.size() << " faces ("
            << args.levels << " levels of " << SubdivisionSchemeName(scheme)
            << " over " << base.faces.size() << " base faces)\n";
  return Status::Ok();
}

}  // namespace

void AddSubdivideCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<SubdivideArgs>();
  CLI::App* cmd = app.add_subcommand(
      "subdivide",
      "Refine a coarse manifold mesh by 1-to-4 splits into a semi-regular mesh");
  cmd->add_option("in", args->in, "Coarse manifold mesh (.ply, .obj, .off, .glb, .gltf)")
      ->required();
  cmd->add_option("out", args->out, "Output mesh (.ply, .obj, .glb or .gltf)")->required();
  cmd->add_option("-l,--levels", args->levels, "Levels of subdivision")
      ->check(CLI::Range(0, kMaxStreamLevels))
      ->capture_default_str();
  cmd->add_option("-s,--scheme", args->scheme,
                  "midpoint, loop or butterfly (modified butterfly)")
      ->check(CLI::IsMember({"midpoint", "loop", "butterfly"}))
      ->capture_default_str();
  cmd->add_flag("!--no-clean", args->clean,
                "Do not merge duplicate vertices or drop bad faces first");
  cmd->callback([args, &exit_code] {
    const Status s = Run(*args);
    if (!s.ok()) exit_code = Fail("subdivide", s);
  });
}

}  // namespace meshwave::cli
