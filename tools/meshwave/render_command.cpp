// meshwave render MESH OUT.png [--reference ORIG | --plain]: an off-screen
// picture of a mesh as it looks (base colour texture, vertex colours,
// material colour; grey without them), or of its geometry alone: grey with
// --plain, or coloured by each vertex's distance to the same vertex of a
// reference as in Satti et al. 2011, Figs. 11-12: green (no error) to pure
// red at a threshold given as a fraction of the reference's bounding-box
// diagonal.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "appearance_shader.h"
#include "cli_util.h"
#include "commands.h"
#include "core/durable_file.h"
#include "meshwave/mesh.h"
#include "meshwave/mesh_asset.h"
#include "meshwave/mesh_io.h"
#include "png_writer.h"
#include "rasterizer.h"

namespace meshwave::cli {
namespace {

struct RenderArgs {
  std::string in, out, reference, view = "0,0";
  int width = 800, height = 800;
  double threshold = 0.001;  // 0.1 % of the diagonal, as Satti et al. 2011
  bool plain = false;
};

Result<View> ParseView(const RenderArgs& args) {
  View v;
  std::istringstream ss(args.view);
  char comma = 0;
  if (!(ss >> v.azimuth_deg >> comma >> v.elevation_deg) || comma != ',' ||
      !std::isfinite(v.azimuth_deg) || !std::isfinite(v.elevation_deg)) {
    return InvalidArgument("--view wants AZIMUTH,ELEVATION in degrees, e.g. 30,15");
  }
  v.width = args.width;
  v.height = args.height;
  return v;
}

// Green (no error) to red (at the threshold) per vertex of `mesh`.
Result<std::vector<Vec3>> ErrorColours(const TriMesh& mesh, const RenderArgs& args) {
  const Vec3 green(0.1, 0.75, 0.1), red(0.9, 0.05, 0.05);
  MW_ASSIGN_OR_RETURN(TriMesh ref, ReadMesh(args.reference));
  if (ref.positions.size() != mesh.positions.size()) {
    return InvalidArgument(
        "the reference has " + std::to_string(ref.positions.size()) + " vertices, " + args.in +
        " has " + std::to_string(mesh.positions.size()) +
        " (colours compare vertex i with vertex i: use a decoded mesh and the full "
        "decode of the same stream)");
  }
  Vec3 lo = ref.positions[0], hi = lo;
  for (const Vec3& p : ref.positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double limit = args.threshold * (hi - lo).norm();
  double worst = 0;
  std::vector<Vec3> colours(mesh.positions.size());
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const double d = (mesh.positions[i] - ref.positions[i]).norm();
    worst = std::max(worst, d);
    const double t = limit > 0 ? std::min(1.0, d / limit) : 0.0;
    colours[i] = (1 - t) * green + t * red;
  }
  std::fprintf(stderr, "largest vertex error %.3g (%.4f %% of the diagonal); red from %.4f %%\n",
               worst, 100 * worst / (hi - lo).norm(), 100 * args.threshold);
  return colours;
}

// The geometry alone, read as before attributes were drawn (ReadMesh: the
// vertex order --reference relies on), grey or coloured by error.
Result<std::vector<uint8_t>> RenderGeometry(const RenderArgs& args, const View& view) {
  MW_ASSIGN_OR_RETURN(TriMesh mesh, ReadMesh(args.in));
  if (mesh.faces.empty()) return InvalidArgument(args.in + ": no faces to render");
  std::vector<Vec3> colours(mesh.positions.size(), Vec3(0.7, 0.7, 0.7));
  if (!args.reference.empty()) {
    MW_ASSIGN_OR_RETURN(colours, ErrorColours(mesh, args));
  }
  return Rasterize(mesh, colours, view);
}

// What the mesh looks like. An asset with nothing but geometry goes the
// geometry way, so that it renders to the same pixels as before.
Result<std::vector<uint8_t>> RenderAppearance(const RenderArgs& args, const View& view) {
  Result<MeshAsset> asset = ReadMeshAsset(args.in);
  if (!asset.ok()) {
    // Where the geometry reads but what the file refers to (a texture, a
    // material library) does not, say how to draw what can be drawn.
    if (!ReadMesh(args.in).ok()) return asset.status();
    return Status(asset.status().code(),
                  asset.status().message() + " (--plain draws the geometry alone)");
  }
  if (!HasAppearance(*asset)) return RenderGeometry(args, view);
  if (asset->mesh.faces.empty()) return InvalidArgument(args.in + ": no faces to render");
  return Rasterize(asset->mesh, AppearanceShader(*asset), view);
}

Status Run(const RenderArgs& args) {
  MW_ASSIGN_OR_RETURN(View view, ParseView(args));
  if (args.plain && !args.reference.empty()) {
    return InvalidArgument("--plain and --reference both choose the colours: give one");
  }
  const bool geometry = args.plain || !args.reference.empty();
  MW_ASSIGN_OR_RETURN(const std::vector<uint8_t> rgb,
                      geometry ? RenderGeometry(args, view) : RenderAppearance(args, view));
  MW_ASSIGN_OR_RETURN(std::string png, EncodePng(view.width, view.height, rgb));
  return WriteFileDurably(args.out, png);
}

}  // namespace

void AddRenderCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand(
      "render",
      "Render a mesh to PNG off-screen as it looks: base colour texture (glTF, OBJ + MTL), "
      "vertex colours (PLY, glTF) and material colour, grey without them; or its geometry "
      "alone: grey (--plain) or coloured by the distance of each vertex to a reference "
      "(--reference, green to red)");
  cmd->add_option("mesh", args->in, "Mesh file (.ply, .obj, .off, .glb, .gltf)")->required();
  cmd->add_option("out", args->out, "Output image (.png)")->required();
  cmd->add_option("--reference", args->reference,
                  "Colour by geometry error against this mesh, with the same vertices in the "
                  "same order (e.g. the full decode); textures and colours are not drawn");
  cmd->add_flag("--plain", args->plain, "Grey geometry: textures and colours are not drawn");
  cmd->add_option("--view", args->view, "AZIMUTH,ELEVATION in degrees")->capture_default_str();
  cmd->add_option("--width", args->width, "Image width")->check(CLI::Range(16, 8192))->capture_default_str();
  cmd->add_option("--height", args->height, "Image height")->check(CLI::Range(16, 8192))->capture_default_str();
  cmd->add_option("--threshold", args->threshold,
                  "Distance shown pure red, as a fraction of the reference's diagonal "
                  "(Satti et al. 2011: 0.001 low rates, 0.0002 high rates)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->callback([args, &exit_code] {
    const Status s = Run(*args);
    if (!s.ok()) exit_code = Fail("render", s);
  });
}

}  // namespace meshwave::cli
