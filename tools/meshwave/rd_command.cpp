// meshwave rd IN --coders 3xc,sim,pgc [--csv OUT] [--json]: rate-distortion
// curves of the bitplane coders on one mesh, and PSNR at the rates of the
// comparisons of Satti et al. 2011 (base mesh excluded, as in its figures).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "cli_util.h"
#include "commands.h"
#include "core/durable_file.h"
#include "meshwave.pb.h"
#include "meshwave/mesh.h"
#include "meshwave/mesh_clean.h"
#include "meshwave/mesh_io.h"
#include "meshwave/rate_distortion.h"
#include "meshwave/remesh.h"
#include "meshwave/semiregular.h"
#include "meshwave/subdivision.h"

namespace meshwave::cli {
namespace {

struct RdArgs {
  std::string in, csv, coders = "3xc,sim,pgc", predictor = "butterfly",
                       update = "";
  QuantizerArgs quantizer;
  int levels = -1;
  int precision = 16;
  uint32_t leaf_size = EncodeOptions{}.octree_leaf_size;
  bool json = false;
  uint32_t sawt_alpha = EncodeOptions{}.sawt_alpha;
  double sawt_lambda = EncodeOptions{}.sawt_lambda_scale;
};

struct LoadedMesh {
  SemiRegularMesh mesh;
  bool remeshed = false;
};

// Semi-regular input as it is (canonical order); anything else remeshed.
Result<LoadedMesh> Load(const RdArgs& args) {
  MW_ASSIGN_OR_RETURN(TriMesh mesh, ReadMesh(args.in));
  CleanMesh(mesh);
  auto detected = DetectSemiRegular(mesh);
  if (detected.ok()) {
    std::cerr << args.in << ": semi-regular, " << detected->mesh.levels()
              << " levels over " << detected->mesh.hierarchy->faces(0).size()
              << " base faces\n";
    return LoadedMesh{std::move(detected->mesh), false};
  }
  std::cerr << args.in << ": not semi-regular (" << detected.status().message()
            << "); remeshing first\n";
  RemeshOptions options;
  options.levels = args.levels;
  MW_ASSIGN_OR_RETURN(RemeshResult remeshed, Remesh(mesh, options));
  for (const auto& w : remeshed.warnings) std::cerr << "warning: " << w << "\n";
  std::cerr << "remeshed: " << remeshed.levels << " levels over "
            << remeshed.base_faces << " base faces, " << remeshed.finest_vertices
            << " vertices\n";
  return LoadedMesh{std::move(remeshed.mesh), true};
}

Result<std::vector<RdCoder>> ParseCoders(const std::string& list) {
  std::vector<RdCoder> out;
  std::stringstream in(list);
  std::string name;
  while (std::getline(in, name, ',')) {
    if (name.empty()) continue;
    MW_ASSIGN_OR_RETURN(RdCoder coder, ParseRdCoder(name));
    out.push_back(coder);
  }
  if (out.empty()) return InvalidArgument("--coders names no coder");
  return out;
}

std::string Csv(const std::vector<RdCurve>& curves) {
  std::string out = "coder,packets,bytes_total,bpv_total,bpv_excl_base,psnr_db\n";
  char line[256];
  for (const RdCurve& c : curves) {
    for (const RdPoint& p : c.points) {
      std::snprintf(line, sizeof line, "%s,%zu,%llu,%.6f,%.6f,%.4f\n",
                    RdCoderName(c.coder), p.packets,
                    static_cast<unsigned long long>(p.bytes_total), p.bpv_total,
                    p.bpv_excl_base, p.psnr_db);
      out += line;
    }
  }
  return out;
}

void PrintTable(const RdArgs& args, const SemiRegularMesh& mesh,
                const std::vector<RdCurve>& curves) {
  std::printf("%s: %llu vertices, %d levels, %zu base vertices; %s/%s, precision %d\n",
              args.in.c_str(),
              static_cast<unsigned long long>(mesh.positions.size()), mesh.levels(),
              static_cast<size_t>(mesh.hierarchy->vertex_count(0)),
              args.predictor.c_str(), args.update.c_str(), args.precision);
  std::printf("PSNR [dB] at bits per vertex, base mesh excluded (packet-granular "
              "curves, linear interpolation)\n");
  std::printf("%-6s", "coder");
  for (double bpv : kRdTableBpv) std::printf(" %8.2f", bpv);
  std::printf("   packets  base bpv  full bpv  full PSNR\n");
  for (const RdCurve& c : curves) {
    std::printf("%-6s", RdCoderName(c.coder));
    for (double bpv : kRdTableBpv) {
      const double psnr = PsnrAtBpv(c, bpv);
      if (std::isnan(psnr)) {
        std::printf(" %8s", "-");
      } else {
        std::printf(" %8.2f", psnr);
      }
    }
    const RdPoint& first = c.points.front();
    const RdPoint& last = c.points.back();
    std::printf("   %7zu  %8.3f  %8.3f  %9.2f\n", last.packets, first.bpv_total,
                last.bpv_total, last.psnr_db);
  }
}

// Rates where every coder has completed the same bitplane: there they all
// reconstruct the same mesh, so the rates compare exactly.
void PrintEqualQuality(const std::vector<RdCurve>& curves) {
  int top = -1;
  for (const RdPoint& p : curves.front().points) top = std::max(top, p.bitplane_complete);
  std::printf("\nRate at equal quality: bpv (base excluded) when bitplane b is complete\n");
  std::printf("%8s %8s", "bitplane", "PSNR");
  for (const RdCurve& c : curves) std::printf(" %9s", RdCoderName(c.coder));
  std::printf("\n");
  for (int b = top; b >= 0; --b) {
    std::vector<const RdPoint*> at;
    for (const RdCurve& c : curves) at.push_back(PointAtBitplane(c, b));
    if (std::count(at.begin(), at.end(), nullptr) > 0) continue;
    std::printf("%8d %8.2f", b, at.front()->psnr_db);
    for (const RdPoint* p : at) std::printf(" %9.4f", p->bpv_excl_base);
    std::printf("\n");
  }
}

proto::RdReport Report(const RdArgs& args, const LoadedMesh& loaded,
                       const std::vector<RdCurve>& curves) {
  proto::RdReport r;
  r.set_input(args.in);
  r.set_remeshed(loaded.remeshed);
  r.set_vertices(loaded.mesh.positions.size());
  r.set_levels(static_cast<uint32_t>(loaded.mesh.levels()));
  r.set_base_vertices(loaded.mesh.hierarchy->vertex_count(0));
  r.set_transform(args.predictor);
  r.set_update(args.update);
  r.set_precision(args.precision);
  for (const RdCurve& c : curves) {
    proto::RdCurveReport& out = *r.add_curves();
    out.set_coder(RdCoderName(c.coder));
    for (const RdPoint& p : c.points) {
      proto::RdPointReport& q = *out.add_points();
      q.set_packets(p.packets);
      q.set_bytes_total(p.bytes_total);
      q.set_payload_bytes(p.payload_bytes);
      q.set_bpv_total(p.bpv_total);
      q.set_bpv_excl_base(p.bpv_excl_base);
      q.set_psnr_db(p.psnr_db);
      q.set_bitplane_complete(p.bitplane_complete);
    }
    for (double bpv : kRdTableBpv) {
      proto::RdTableEntry& e = *out.add_table();
      e.set_bpv_excl_base(bpv);
      e.set_psnr_db(PsnrAtBpv(c, bpv));
    }
  }
  return r;
}

Status Run(const RdArgs& given) {
  EncodeOptions options;
  MW_RETURN_IF_ERROR(
      ApplyTransformOptions(given.predictor, given.update, given.precision, options));
  RdArgs args = given;  // with the update resolved, as the report prints it
  args.update = UpdateWeightsName(options.transform.update);
  options.sawt_alpha = args.sawt_alpha;
  options.sawt_lambda_scale = args.sawt_lambda;
  options.octree_leaf_size = args.leaf_size;
  MW_RETURN_IF_ERROR(ApplyQuantizerOption(args.quantizer, options));
  options.name = std::filesystem::path(args.in).stem().string();
  MW_ASSIGN_OR_RETURN(std::vector<RdCoder> coders, ParseCoders(args.coders));
  if (options.auto_deadzone &&
      std::find(coders.begin(), coders.end(), RdCoder::kPgc) != coders.end()) {
    return InvalidArgument("--quantizer auto applies to 3xc and sim; PGC keeps one deadzone");
  }
  MW_ASSIGN_OR_RETURN(LoadedMesh loaded, Load(args));
  std::vector<RdCurve> curves;
  for (RdCoder coder : coders) {
    auto curve = MeasureRdCurve(loaded.mesh, coder, options);
    if (!curve.ok()) return curve.status().WithContext(RdCoderName(coder));
    curves.push_back(*std::move(curve));
  }
  if (!args.csv.empty()) MW_RETURN_IF_ERROR(WriteFileDurably(args.csv, Csv(curves)));
  if (args.json) {
    PrintJson(Report(args, loaded, curves));
  } else {
    PrintTable(args, loaded.mesh, curves);
    PrintEqualQuality(curves);
  }
  return Status::Ok();
}

}  // namespace

void AddRdCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<RdArgs>();
  CLI::App* cmd = app.add_subcommand(
      "rd", "Rate-distortion curves of the 3xC, SIM and PGC coders on a mesh "
            "(irregular meshes are remeshed first)");
  cmd->add_option("in", args->in, "Mesh file (.ply, .obj, .off, .glb, .gltf)")->required();
  cmd->add_option("--coders", args->coders, "Comma-separated: 3xc, sim, pgc")
      ->capture_default_str();
  cmd->add_option("--csv", args->csv,
                  "Write every curve point: coder,packets,bytes_total,bpv_total,"
                  "bpv_excl_base,psnr_db");
  AddTransformOptions(cmd, args->predictor, args->update, args->levels,
                      args->precision);
  AddSawtOptions(cmd, args->sawt_alpha, args->sawt_lambda);
  cmd->add_option("--leaf-size", args->leaf_size,
                  "Octree leaf size of SIM and 3xC (coefficients coded one by one "
                  "below it)")
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
  AddQuantizerOption(cmd, args->quantizer);
  cmd->add_flag("--json", args->json, "Print the curves as JSON instead of a table");
  cmd->callback([args, &exit_code] {
    const Status s = Run(*args);
    if (!s.ok()) exit_code = Fail("rd", s);
  });
}

}  // namespace meshwave::cli
