// meshwave remesh IN OUT [--levels J] [--base-faces N] [--json]: turns any
// triangle mesh into a semi-regular mesh that follows its surface.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "cli_util.h"
#include "commands.h"
#include "scaled_distance.h"
#include "meshwave.pb.h"
#include "meshwave/fidelity.h"
#include "meshwave/mesh.h"
#include "meshwave/mesh_io.h"
#include "meshwave/metrics.h"
#include "meshwave/remesh.h"

namespace meshwave::cli {
namespace {

struct RemeshArgs {
  std::string in, out;
  int levels = -1;
  int base_faces = -1;
  int relax_rounds = RemeshOptions{}.relax_rounds;
  int least_squares_rounds = RemeshOptions{}.least_squares_rounds;
  int threads = RemeshOptions{}.threads;
  bool drop_tiny = false;
  bool json = false;
  bool measure = true;
  // Fewer samples than `meshwave compare` (10 per face): the figures come
  // with the remesh for free in seconds; use compare for the record.
  double samples_per_face = 2;
  double fidelity_db = kDefaultFidelityDb;
  double max_vertex_ratio = kDefaultMaxVertexRatio;
};

// Progress on stderr, redrawn in place, only when stderr is a terminal.
class ProgressLine {
 public:
  ProgressLine() : enabled_(::isatty(STDERR_FILENO) == 1) {}
  ~ProgressLine() { Finish(); }

  void Update(std::string_view stage, double fraction) {
    if (!enabled_) return;
    const int percent = static_cast<int>(std::lround(100 * fraction));
    if (percent == last_percent_ && stage == last_stage_) return;
    last_percent_ = percent;
    last_stage_ = std::string(stage);
    std::fprintf(stderr, "\rremesh: %-9s %3d %%", last_stage_.c_str(), percent);
    std::fflush(stderr);
    drawn_ = true;
  }

  void Finish() {
    if (drawn_) std::fprintf(stderr, "\r%*s\r", 40, "");
    drawn_ = false;
  }

 private:
  bool enabled_;
  bool drawn_ = false;
  int last_percent_ = -1;
  std::string last_stage_;
};

void FillReport(const RemeshResult& r, proto::RemeshReport& p) {
  proto::Cleaning& c = *p.mutable_cleaning();
  c.set_merged_vertices(r.cleaning.merged_vertices);
  c.set_degenerate_faces(r.cleaning.degenerate_faces);
  c.set_duplicate_faces(r.cleaning.duplicate_faces);
  c.set_unreferenced_vertices(r.cleaning.unreferenced_vertices);
  c.set_zero_area_faces(r.cleaning.zero_area_faces);
  p.set_input_vertices(r.input_vertices);
  p.set_input_faces(r.input_faces);
  p.set_components(r.components);
  p.set_dropped_components(r.dropped_components);
  p.set_dropped_faces(r.dropped_faces);
  p.set_tiny_components(r.tiny_components);
  p.set_non_manifold_edges(r.non_manifold_edges);
  p.set_non_manifold_vertices(r.non_manifold_vertices);
  p.set_split_vertex_copies(r.split_vertex_copies);
  p.set_reoriented_faces(r.reoriented_faces);
  p.set_levels(static_cast<uint32_t>(r.levels));
  p.set_target_base_faces(r.target_base_faces);
  p.set_base_vertices(r.base_vertices);
  p.set_base_faces(r.base_faces);
  p.set_finest_vertices(r.finest_vertices);
  p.set_finest_faces(r.finest_faces);
  p.set_flipped_faces(r.flipped_faces);
  p.set_degenerate_faces(r.degenerate_faces);
  p.set_min_angle_degrees(r.min_angle_degrees);
  p.set_normal_hits(r.normal_hits);
  p.set_closest_fallbacks(r.closest_fallbacks);
  p.set_boundary_vertices(r.boundary_vertices);
  p.set_locked_features(r.locked_features);
  p.set_seconds(r.seconds);
  for (const auto& [stage, seconds] : r.stage_seconds) {
    (*p.mutable_stage_seconds())[stage] = seconds;
  }
  for (const std::string& w : r.warnings) p.add_warnings(w);
}

Status Measure(const RemeshArgs& args, const TriMesh& input,
               const TriMesh& remeshed, proto::RemeshReport& report) {
  const auto start = std::chrono::steady_clock::now();
  SurfaceDistanceOptions options;
  options.samples_per_face = args.samples_per_face;
  auto d = SymmetricSurfaceDistance(input, remeshed, options);
  if (!d.ok()) return d.status().WithContext("measuring the remesh");
  const double diagonal = d->diagonal;
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
  s.set_samples_per_face(options.samples_per_face);
  s.set_seed(options.seed);
  report.set_measure_seconds(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count());
  return Status::Ok();
}

void PrintHuman(const proto::RemeshReport& r) {
  const auto line = [](const char* key, const std::string& value) {
    std::printf("%-22s %s\n", key, value.c_str());
  };
  const auto num = [](uint64_t v) { return std::to_string(v); };
  char buffer[128];
  line("input:", r.input() + " (" + num(r.input_vertices()) + " vertices, " +
                     num(r.input_faces()) + " faces, " + num(r.components()) +
                     " components after repair)");
  line("output:", r.output());
  line("levels:", num(r.levels()));
  line("base:", num(r.base_vertices()) + " vertices, " + num(r.base_faces()) +
                    " faces (" + num(r.target_base_faces()) + " planned)");
  line("finest:", num(r.finest_vertices()) + " vertices, " +
                      num(r.finest_faces()) + " faces");
  line("flipped faces:", num(r.flipped_faces()));
  line("degenerate faces:", num(r.degenerate_faces()));
  std::snprintf(buffer, sizeof buffer, "%.3g°", r.min_angle_degrees());
  line("smallest angle:", buffer);
  if (r.has_surface()) {
    std::snprintf(buffer, sizeof buffer, "%.4f %% of diagonal",
                  r.surface().rms().percent_of_diagonal());
    line("surface rms:", buffer);
    std::snprintf(buffer, sizeof buffer, "%.4f %% of diagonal",
                  r.surface().hausdorff().percent_of_diagonal());
    line("hausdorff:", buffer);
  }
  if (r.fidelity_asked_db() > 0) {
    std::snprintf(buffer, sizeof buffer, "%.2f dB after %u attempt%s (asked %.2f dB)",
                  r.fidelity_reached_db(), r.remesh_attempts(),
                  r.remesh_attempts() == 1 ? "" : "s", r.fidelity_asked_db());
    line("fidelity:", buffer);
  }
  std::snprintf(buffer, sizeof buffer, "%.2f s", r.seconds());
  line("time:", buffer);
}

Status Run(const RemeshArgs& args) {
  MW_ASSIGN_OR_RETURN(const TriMesh input, ReadMesh(args.in));
  RemeshOptions options;
  options.levels = args.levels;
  options.base_faces = args.base_faces;
  options.relax_rounds = args.relax_rounds;
  options.least_squares_rounds = args.least_squares_rounds;
  options.threads = args.threads;
  options.drop_tiny_components = args.drop_tiny;
  ProgressLine progress;
  options.progress = [&progress](std::string_view stage, double fraction) {
    progress.Update(stage, fraction);
  };
  Result<RemeshResult> result = Status(StatusCode::kInternal, "not remeshed");
  FidelityRemesh fitted;
  if (args.fidelity_db > 0) {
    auto f = RemeshToFidelity(input, options, args.fidelity_db, args.max_vertex_ratio);
    if (f.ok()) {
      fitted = std::move(*f);
      result = std::move(fitted.result);
    } else {
      result = f.status();
    }
  } else {
    result = Remesh(input, options);
  }
  progress.Finish();
  if (!result.ok()) return result.status().WithContext(args.in);
  const TriMesh finest = result->mesh.Finest();
  MW_RETURN_IF_ERROR(WriteMesh(finest, args.out));

  proto::RemeshReport report;
  report.set_input(args.in);
  report.set_output(args.out);
  report.set_file_vertices(input.positions.size());
  report.set_file_faces(input.faces.size());
  FillReport(*result, report);
  if (args.fidelity_db > 0) {
    report.set_fidelity_asked_db(args.fidelity_db);
    report.set_fidelity_reached_db(fitted.psnr_db);
    report.set_remesh_attempts(static_cast<uint32_t>(fitted.attempts));
    if (fitted.psnr_db < args.fidelity_db) {
      std::fprintf(stderr,
                   "meshwave remesh: warning: fidelity %.2f dB not reached (%.2f dB with %zu "
                   "finest vertices; --max-vertex-ratio %g)\n",
                   args.fidelity_db, fitted.psnr_db, result->finest_vertices,
                   args.max_vertex_ratio);
    }
  }
  if (args.measure) MW_RETURN_IF_ERROR(Measure(args, input, finest, report));
  for (const std::string& w : result->warnings) {
    std::cerr << "meshwave remesh: warning: " << w << "\n";
  }
  if (args.json) {
    PrintJson(report);
  } else {
    PrintHuman(report);
  }
  return Status::Ok();
}

}  // namespace

void AddRemeshCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<RemeshArgs>();
  CLI::App* cmd = app.add_subcommand(
      "remesh",
      "Turn any triangle mesh into a semi-regular mesh that follows its "
      "surface (clean, repair, simplify to a base mesh, subdivide and fit)");
  cmd->add_option("in", args->in, "Input mesh (.ply, .obj, .off, .glb, .gltf)")->required();
  cmd->add_option("out", args->out, "Semi-regular output (.ply, .obj, .glb or .gltf)")
      ->required();
  AddFidelityOptions(cmd, args->fidelity_db, args->max_vertex_ratio, "the remesh");
  cmd->add_option("-l,--levels", args->levels,
                  "Levels of 1-to-4 subdivision (-1: from the input size)")
      ->check(CLI::Range(-1, 8))
      ->capture_default_str();
  cmd->add_option("-n,--base-faces", args->base_faces,
                  "About how many base faces (-1: so that the finest level "
                  "has about as many vertices as the input)")
      ->check(CLI::Range(-1, 1 << 30))
      ->capture_default_str();
  cmd->add_option("--relax-rounds", args->relax_rounds,
                  "Tangential relaxation rounds per level")
      ->check(CLI::Range(0, 50))
      ->capture_default_str();
  cmd->add_option("--least-squares-rounds", args->least_squares_rounds,
                  "Least-squares rounds after the fit: finest vertices move along their "
                  "normals to lie closer to the input (0: off, an interpolating remesh)")
      ->check(CLI::Range(0, 10))
      ->capture_default_str();
  AddThreadsOption(cmd, args->threads);
  cmd->add_flag("--drop-tiny", args->drop_tiny,
                "Drop components of fewer than 8 faces instead of keeping "
                "each as its own small base");
  cmd->add_flag("--json", args->json,
                "Print a RemeshReport as JSON instead of text");
  cmd->add_flag("!--no-measure", args->measure,
                "Skip the surface distance between input and output");
  cmd->add_option("--samples-per-face", args->samples_per_face,
                  "Surface samples per face for the distance figures")
      ->check(CLI::Range(0.0, 1000.0))
      ->capture_default_str();
  cmd->callback([args, &exit_code] {
    const Status s = Run(*args);
    if (!s.ok()) exit_code = Fail("remesh", s);
  });
}

}  // namespace meshwave::cli
