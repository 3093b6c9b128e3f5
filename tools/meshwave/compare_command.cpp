// meshwave compare A B [--json] [--samples-per-face N] [--seed S]: vertex
// error (with PSNR) and the symmetric surface distance between two meshes.
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "cli_util.h"
#include "commands.h"
#include "scaled_distance.h"
#include "meshwave.pb.h"
#include "meshwave/mesh.h"
#include "meshwave/mesh_io.h"
#include "meshwave/mesh_stats.h"
#include "meshwave/metrics.h"

namespace meshwave::cli {
namespace {

// Same-index matching is replaced by nearest-neighbour matching only when
// the latter explains the vertices far better (RMS at least this many times
// smaller) and is nearly one-to-one. For a decoded mesh in the original
// order nearest matching can only be somewhat smaller (it may pick a closer
// wrong vertex when the error nears the vertex spacing); for a reordered
// copy same-index RMS is of the order of the mesh size and nearest RMS is
// about the coding error.
constexpr double kReorderRmsRatio = 10;
constexpr double kReorderMinDistinctFraction = 0.9;

struct CompareArgs {
  std::string file_a, file_b;
  bool json = false;
  double samples_per_face = SurfaceDistanceOptions{}.samples_per_face;
  uint64_t seed = SurfaceDistanceOptions{}.seed;
  size_t min_samples = SurfaceDistanceOptions{}.min_samples;
  // auto: by index unless nearest-neighbour matching explains B far better
  // (see above); index / nearest: forced, e.g. nearest for a coder that
  // reorders vertices (Draco) at rates where "far better" is not clear.
  std::string match = "auto";
};

// Fills report->vertex_error (when the counts agree) and vertex_note.
Status AddVertexError(const TriMesh& a, const TriMesh& b, double diagonal,
                      const std::string& match, proto::CompareReport& report) {
  if (a.positions.size() != b.positions.size() && match != "nearest") {
    report.set_vertex_note(
        "vertex counts differ (" + std::to_string(a.positions.size()) + " vs " +
        std::to_string(b.positions.size()) + "): no per-vertex error");
    return Status::Ok();
  }
  MW_ASSIGN_OR_RETURN(const VertexErrorStats nearest,
                      VertexErrorByNearest(a.positions, b.positions, diagonal));
  VertexErrorStats same;
  if (a.positions.size() == b.positions.size()) {
    MW_ASSIGN_OR_RETURN(same, VertexError(a.positions, b.positions, diagonal));
  }
  const bool reordered =
      match == "nearest" ||
      (match == "auto" && nearest.rms * kReorderRmsRatio < same.rms &&
       static_cast<double>(nearest.distinct_matches) >=
           kReorderMinDistinctFraction * static_cast<double>(nearest.count));
  const VertexErrorStats& chosen = reordered ? nearest : same;
  proto::VertexErrorReport& v = *report.mutable_vertex_error();
  v.set_matching(reordered ? "nearest_neighbour" : "same_index");
  *v.mutable_rms() = Scaled(chosen.rms, diagonal);
  *v.mutable_max() = Scaled(chosen.max, diagonal);
  *v.mutable_mean() = Scaled(chosen.mean, diagonal);
  v.set_count(chosen.count);
  v.set_distinct_matches(chosen.distinct_matches);
  if (a.positions.size() == b.positions.size()) v.set_same_index_rms(same.rms);
  v.set_nearest_rms(nearest.rms);
  report.set_vertex_note(!reordered          ? "vertices matched by index"
                         : match == "nearest" ? "vertices matched by nearest neighbour (asked)"
                                              : "vertices matched by nearest neighbour (orders differ)");
  return Status::Ok();
}

Result<proto::CompareReport> Compare(const CompareArgs& args) {
  MW_ASSIGN_OR_RETURN(const TriMesh a, ReadMesh(args.file_a));
  MW_ASSIGN_OR_RETURN(const TriMesh b, ReadMesh(args.file_b));
  proto::CompareReport report;
  report.set_file_a(args.file_a);
  report.set_file_b(args.file_b);
  report.set_vertices_a(a.positions.size());
  report.set_vertices_b(b.positions.size());
  report.set_faces_a(a.faces.size());
  report.set_faces_b(b.faces.size());
  const double diagonal = BoundingBox(a.positions).Diagonal();
  if (!(diagonal > 0) || !std::isfinite(diagonal)) {
    return InvalidArgument(args.file_a +
                           ": bounding box has no extent, so there is no "
                           "scale for relative errors");
  }
  report.set_diagonal(diagonal);
  MW_RETURN_IF_ERROR(AddVertexError(a, b, diagonal, args.match, report));

  SurfaceDistanceOptions options;
  options.samples_per_face = args.samples_per_face;
  options.seed = args.seed;
  options.min_samples = args.min_samples;
  auto d = SymmetricSurfaceDistance(a, b, options);
  if (!d.ok()) {
    return d.status().WithContext("surface distance between " + args.file_a +
                                  " and " + args.file_b);
  }
  proto::SurfaceDistanceReport& s = *report.mutable_surface();
  *s.mutable_rms_ab() = Scaled(d->rms_ab, diagonal);
  *s.mutable_rms_ba() = Scaled(d->rms_ba, diagonal);
  *s.mutable_rms() = Scaled(d->rms, diagonal);
  *s.mutable_hausdorff_ab() = Scaled(d->hausdorff_ab, diagonal);
  *s.mutable_hausdorff_ba() = Scaled(d->hausdorff_ba, diagonal);
  *s.mutable_hausdorff() = Scaled(d->hausdorff, diagonal);
  *s.mutable_mean_ab() = Scaled(d->mean_ab, diagonal);
  *s.mutable_mean_ba() = Scaled(d->mean_ba, diagonal);
  *s.mutable_mean() = Scaled(d->mean, diagonal);
  s.set_samples_a(d->samples_a);
  s.set_samples_b(d->samples_b);
  s.set_samples_per_face(args.samples_per_face);
  s.set_seed(args.seed);
  return report;
}

std::string Format(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

std::string Describe(const proto::ScaledDistance& d) {
  return Format("%.6g", d.absolute()) + "  (" +
         Format("%.4g", d.percent_of_diagonal()) + " % of diagonal, PSNR " +
         Format("%.2f", d.psnr_db()) + " dB)";
}

void PrintHuman(const proto::CompareReport& r) {
  const auto line = [](const std::string& key, const std::string& value) {
    std::printf("%-26s %s\n", (key + ":").c_str(), value.c_str());
  };
  const auto num = [](uint64_t v) { return std::to_string(v); };
  line("file A", r.file_a());
  line("file B", r.file_b());
  line("vertices",
       num(r.vertices_a()) + " (A), " + num(r.vertices_b()) + " (B)");
  line("faces", num(r.faces_a()) + " (A), " + num(r.faces_b()) + " (B)");
  line("diagonal of A (peak)", Format("%.6g", r.diagonal()));
  line("vertex matching", r.vertex_note());
  if (r.has_vertex_error()) {
    const proto::VertexErrorReport& v = r.vertex_error();
    line("vertex rms", Describe(v.rms()));
    line("vertex max", Describe(v.max()));
    line("vertex mean", Describe(v.mean()));
    if (v.matching() == "nearest_neighbour") {
      line("vertex rms by index", Format("%.6g", v.same_index_rms()));
      line("distinct matches",
           num(v.distinct_matches()) + " of " + num(v.count()));
    }
  }
  const proto::SurfaceDistanceReport& s = r.surface();
  line("surface samples", num(s.samples_a()) + " on A, " + num(s.samples_b()) +
                              " on B (seed " + num(s.seed()) + ")");
  line("surface rms A->B", Describe(s.rms_ab()));
  line("surface rms B->A", Describe(s.rms_ba()));
  line("surface rms (max of both)", Describe(s.rms()));
  line("surface mean A->B", Describe(s.mean_ab()));
  line("surface mean B->A", Describe(s.mean_ba()));
  line("hausdorff A->B", Describe(s.hausdorff_ab()));
  line("hausdorff B->A", Describe(s.hausdorff_ba()));
  line("hausdorff", Describe(s.hausdorff()));
}

}  // namespace

void AddCompareCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* cmd = app.add_subcommand(
      "compare",
      "Measure how far mesh B is from mesh A: per-vertex error and PSNR when "
      "the vertex counts agree, and always the symmetric sampled surface "
      "distance (RMS, mean, Hausdorff); relative values use the bounding-box "
      "diagonal of A");
  cmd->add_option("a", args->file_a, "Reference mesh A (.ply, .obj, .off, .glb, .gltf)")
      ->required();
  cmd->add_option("b", args->file_b, "Mesh B to measure against A")->required();
  cmd->add_flag("--json", args->json,
                "Print a CompareReport as JSON instead of text");
  cmd->add_option("--samples-per-face", args->samples_per_face,
                  "Surface samples per face of the mesh with more faces; "
                  "each mesh gets that many in total, spread by area")
      ->check(CLI::Range(0.0, 1000.0))
      ->capture_default_str();
  cmd->add_option("--min-samples", args->min_samples,
                  "At least this many surface samples on each mesh")
      ->check(CLI::Range(size_t{0}, size_t{1} << 31))
      ->capture_default_str();
  cmd->add_option("--match", args->match,
                  "Vertex matching for the per-vertex error: auto (by index "
                  "unless the orders clearly differ), index, or nearest "
                  "(each vertex of A against the nearest vertex of B)")
      ->check(CLI::IsMember({"auto", "index", "nearest"}))
      ->capture_default_str();
  cmd->add_option("--seed", args->seed,
                  "Seed of the random surface samples (same seed, same "
                  "result on every platform)")
      ->capture_default_str();
  cmd->callback([args, &exit_code] {
    auto report = Compare(*args);
    if (!report.ok()) {
      exit_code = Fail("compare", report.status());
      return;
    }
    if (args->json) {
      PrintJson(*report);
    } else {
      PrintHuman(*report);
    }
  });
}

}  // namespace meshwave::cli
