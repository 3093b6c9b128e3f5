// meshwave render-compare REFERENCE MESH...: how alike each mesh looks to
// the reference, as a textured mesh's user sees it (rendered_psnr.h).
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cli_util.h"
#include "commands.h"
#include "core/durable_file.h"
#include "meshwave/mesh_asset.h"
#include "png_writer.h"
#include "rendered_psnr.h"

namespace meshwave::cli {
namespace {

struct RenderCompareArgs {
  std::string reference;
  std::vector<std::string> meshes;
  RenderedPsnrOptions options;
  std::string pictures;  // a directory for the PNGs, or empty
};

Result<MeshAsset> ReadForRender(const std::string& path) {
  MW_ASSIGN_OR_RETURN(MeshAsset asset, ReadMeshAsset(path));
  if (asset.mesh.faces.empty()) return InvalidArgument(path + ": no faces to render");
  return asset;
}

Status WritePictures(const std::string& dir, const std::string& stem, const Pictures& p,
                     const std::vector<View>& views) {
  for (size_t v = 0; v < p.rgb.size(); ++v) {
    MW_ASSIGN_OR_RETURN(std::string png, EncodePng(views[v].width, views[v].height, p.rgb[v]));
    MW_RETURN_IF_ERROR(
        WriteFileDurably(dir + "/" + stem + "_view" + std::to_string(v) + ".png", png));
  }
  return Status::Ok();
}

Status Run(const RenderCompareArgs& args) {
  MW_ASSIGN_OR_RETURN(const MeshAsset reference, ReadForRender(args.reference));
  std::vector<View> views = MetricViews(args.options.views, args.options.size);
  const Pictures ref = RenderReference(reference, views, args.options);
  if (!args.pictures.empty()) {
    MW_RETURN_IF_ERROR(WritePictures(args.pictures, "reference", ref, views));
  }
  Status first_error = Status::Ok();
  for (size_t i = 0; i < args.meshes.size(); ++i) {
    // One unreadable mesh of a batch is reported and the others measured.
    Result<MeshAsset> mesh = ReadForRender(args.meshes[i]);
    if (!mesh.ok()) {
      std::fprintf(stderr, "render-compare: %s\n", mesh.status().message().c_str());
      if (first_error.ok()) first_error = mesh.status();
      continue;
    }
    const Pictures pictures = RenderLike(*mesh, views, args.options);
    if (!args.pictures.empty()) {
      MW_RETURN_IF_ERROR(WritePictures(args.pictures, "mesh" + std::to_string(i), pictures, views));
    }
    const LumaPsnr psnr = CompareLuma(ref, pictures);
    std::printf("%.3f\t%llu\t%s\n", psnr.db, static_cast<unsigned long long>(psnr.object_pixels),
                args.meshes[i].c_str());
    std::fflush(stdout);
  }
  return first_error;
}

}  // namespace

void AddRenderCompareCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<RenderCompareArgs>();
  CLI::App* cmd = app.add_subcommand(
      "render-compare",
      "How alike meshes look to a reference, as a user sees a textured mesh: each rendered "
      "from the same cameras around the reference (base colour texture, vertex or material "
      "colour, without light), and the luma (BT.709) PSNR over the pixels either covers. "
      "Prints one line per mesh: dB, object pixels, file");
  cmd->add_option("reference", args->reference, "The original (.ply, .obj, .off, .glb, .gltf)")
      ->required();
  cmd->add_option("meshes", args->meshes, "Meshes to measure against it (e.g. decodes)")
      ->required();
  cmd->add_option("--views", args->options.views,
                  "Cameras: half 25 degrees above the equator, half below")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  cmd->add_option("--size", args->options.size, "Pixels a side of each picture")
      ->check(CLI::Range(16, 8192))
      ->capture_default_str();
  cmd->add_option("--supersample", args->options.supersample,
                  "Samples a side per pixel, averaged (antialiased edges, filtered texture)")
      ->check(CLI::Range(1, 8))
      ->capture_default_str();
  cmd->add_flag("--lit", args->options.lit,
                "Shade with the Lambert light of `meshwave render` (geometry's shading counts)");
  cmd->add_option("--pictures", args->pictures,
                  "Write every picture here as PNG (reference_viewK.png, meshI_viewK.png)")
      ->check(CLI::ExistingDirectory);
  cmd->callback([args, &exit_code] {
    const Status s = Run(*args);
    if (!s.ok()) exit_code = Fail("render-compare", s);
  });
}

}  // namespace meshwave::cli
