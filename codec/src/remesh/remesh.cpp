// Remesh (meshwave/remesh.h): clean, repair, simplify, subdivide and fit.
#include "meshwave/remesh.h"

#include <Eigen/Geometry>

#include <chrono>
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <utility>

#include "remesh/base_flips.h"
#include "remesh/coincident_vertices.h"
#include "remesh/components.h"
#include "remesh/input_surface.h"
#include "remesh/level_plan.h"
#include "remesh/manifold_repair.h"
#include "remesh/qem_simplifier.h"
#include "remesh/remesh_quality.h"
#include "remesh/surface_fitting.h"

namespace meshwave {
namespace {

using Clock = std::chrono::steady_clock;

// Every component keeps at least this many base faces (all of its faces
// when it has fewer): an octahedron-like base is the coarsest that still
// lets butterfly subdivision and projection find a closed part's shape.
constexpr uint32_t kMinComponentBaseFaces = 24;

// Put-off collapses (qem_simplifier.h) may shrink a component only down to
// this multiple of its share of the base faces by input faces: small parts
// that cannot shrink cleanly (ogre's claws) still shrink, while a part that
// needs many base faces for its shape (ogre's belt) is not forced into
// folds; the base may then exceed its target.
constexpr double kLateFloorShare = 2.0;

// Share of the progress bar per stage, from timings on igea.ply.
constexpr double kRepairShare = 0.05;
constexpr double kSimplifyShare = 0.45;
constexpr double kFitShare = 0.40;

std::string Count(size_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

Status CheckInput(const TriMesh& input) {
  for (size_t v = 0; v < input.positions.size(); ++v) {
    if (!input.positions[v].allFinite()) {
      return InvalidArgument("vertex " + std::to_string(v) +
                             " has a non-finite coordinate");
    }
  }
  if (input.faces.empty()) return InvalidArgument("the mesh has no faces");
  if (input.positions.size() >= 0xffffffffu) {
    return InvalidArgument("the mesh has more than 2^32 - 2 vertices");
  }
  for (size_t f = 0; f < input.faces.size(); ++f) {
    for (uint32_t v : input.faces[f]) {
      if (v >= input.positions.size()) {
        return InvalidArgument("face " + std::to_string(f) +
                               " refers to vertex " + std::to_string(v) +
                               ", but there are only " +
                               std::to_string(input.positions.size()));
      }
    }
  }
  return Status::Ok();
}

// Keeps the faces whose component is kept; compacts vertices.
TriMesh KeepComponents(const TriMesh& mesh, const remesh::Components& comps,
                       const std::vector<uint8_t>& keep) {
  TriMesh out;
  std::vector<uint32_t> index(mesh.positions.size(), 0xffffffffu);
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    if (!keep[comps.of_face[f]]) continue;
    Face g;
    for (int i = 0; i < 3; ++i) {
      const uint32_t v = mesh.faces[f][i];
      if (index[v] == 0xffffffffu) {
        index[v] = static_cast<uint32_t>(out.positions.size());
        out.positions.push_back(mesh.positions[v]);
      }
      g[i] = index[v];
    }
    out.faces.push_back(g);
  }
  return out;
}

class Pipeline {
 public:
  explicit Pipeline(const RemeshOptions& options) : options_(options) {}

  Result<RemeshResult> Run(const TriMesh& input) {
    const Clock::time_point start = Clock::now();
    stage_start_ = start;
    MW_RETURN_IF_ERROR(CheckInput(input));
    // Validate the options before any work.
    MW_RETURN_IF_ERROR(
        remesh::PlanLevels(input.positions.size(), options_.levels,
                           options_.base_faces)
            .status());

    TriMesh mesh = input;
    result_.cleaning = CleanMesh(mesh);
    if (mesh.faces.empty()) {
      return InvalidArgument(
          "nothing usable: all " + std::to_string(input.faces.size()) +
          " faces repeat a corner or duplicate another face");
    }
    Report("repair", 0);
    const remesh::RepairReport repair = remesh::RepairManifold(mesh);
    result_.non_manifold_edges = repair.non_manifold_edges;
    result_.non_manifold_vertices = repair.non_manifold_vertices;
    result_.split_vertex_copies = repair.added_vertices;
    result_.reoriented_faces = repair.reoriented_faces;
    MW_RETURN_IF_ERROR(DropUnusableComponents(mesh));
    result_.input_vertices = mesh.positions.size();
    result_.input_faces = mesh.faces.size();
    if (repair.non_manifold_edges + repair.non_manifold_vertices +
            repair.reoriented_faces >
        0) {
      Warn("repaired the input: " +
           Count(repair.non_manifold_edges, "non-manifold edge",
                 "non-manifold edges") +
           " cut open, " +
           Count(repair.non_manifold_vertices, "non-manifold vertex",
                 "non-manifold vertices") +
           " split, " + Count(repair.reoriented_faces, "face", "faces") +
           " turned over to agree with their neighbours");
    }
    EndStage("repair");

    MW_ASSIGN_OR_RETURN(const remesh::LevelPlan plan,
                        remesh::PlanLevels(mesh.positions.size(),
                                           options_.levels,
                                           options_.base_faces));
    result_.levels = plan.levels;
    result_.target_base_faces = plan.base_faces;
    remesh::Components components = remesh::LabelComponents(mesh);
    std::vector<uint32_t> faces_per_component(components.count, 0);
    for (uint32_t c : components.of_face) ++faces_per_component[c];
    remesh::SimplifyOptions simplify;
    simplify.target_faces = plan.base_faces;
    simplify.min_faces.resize(components.count);
    simplify.late_floor.resize(components.count);
    const double faces_total = static_cast<double>(mesh.faces.size());
    for (uint32_t c = 0; c < components.count; ++c) {
      simplify.min_faces[c] =
          std::min(faces_per_component[c], kMinComponentBaseFaces);
      simplify.late_floor[c] = static_cast<uint32_t>(std::max<double>(
          simplify.min_faces[c],
          std::round(kLateFloorShare * static_cast<double>(plan.base_faces) *
                     faces_per_component[c] / faces_total)));
    }
    const auto surface = std::make_unique<remesh::InputSurface>(
        std::move(mesh), std::move(components));
    Report("simplify", kRepairShare);
    remesh::SimplifiedMesh base = remesh::SimplifyByEdgeCollapse(
        surface->mesh(), surface->components(), simplify);
    remesh::FlipToImproveAngles(base.mesh);
    EndStage("simplify");

    auto hierarchy = SemiRegularHierarchy::Build(
        static_cast<uint32_t>(base.mesh.positions.size()), base.mesh.faces,
        plan.levels);
    if (!hierarchy.ok()) {
      return hierarchy.status().WithContext("building the remesh hierarchy");
    }
    result_.base_vertices = base.mesh.positions.size();
    result_.base_faces = base.mesh.faces.size();
    std::vector<Vec3> positions;
    std::vector<remesh::SurfaceAnchor> anchors;
    remesh::PlaceBaseVertices(base, *surface, positions, anchors);
    remesh::FitOptions fit;
    fit.relax_rounds = options_.relax_rounds;
    fit.threads = options_.threads;
    fit.progress = [this](int, double f) {
      Report("fit", kRepairShare + kSimplifyShare + kFitShare * f);
    };
    remesh::FitStats stats;
    MW_RETURN_IF_ERROR(remesh::FitLevels(*hierarchy, *surface, fit, positions,
                                         anchors, &stats)
                           .WithContext("fitting the remesh"));
    result_.normal_hits = stats.normal_hits;
    result_.closest_fallbacks = stats.closest_fallbacks;
    result_.boundary_vertices = stats.boundary_vertices;
    result_.mesh.hierarchy = *hierarchy;
    result_.mesh.positions = std::move(positions);
    const int levels = plan.levels;
    const auto& finest_faces = (*hierarchy)->faces(levels);
    remesh::SeparateCoincidentVertices(result_.mesh.positions, finest_faces);
    EndStage("fit");

    Report("check", kRepairShare + kSimplifyShare + kFitShare);
    const TriMesh finest = result_.mesh.Finest();
    std::vector<uint32_t> face_component(finest.faces.size());
    for (size_t f = 0; f < finest.faces.size(); ++f) {
      face_component[f] = anchors[finest.faces[f][0]].component;
    }
    const remesh::QualityFigures quality = remesh::MeasureQuality(
        finest, face_component, *surface, options_.threads);
    result_.flipped_faces = quality.flipped_faces;
    result_.degenerate_faces = quality.degenerate_faces;
    result_.min_angle_degrees = quality.min_angle_degrees;
    result_.finest_vertices = finest.positions.size();
    result_.finest_faces = finest.faces.size();
    EndStage("check");
    AddResultWarnings(stats);
    Report("done", 1);
    result_.seconds =
        std::chrono::duration<double>(Clock::now() - start).count();
    return std::move(result_);
  }

 private:
  static std::vector<double> ComponentAreas(
      const TriMesh& mesh, const remesh::Components& components) {
    std::vector<double> areas(components.count, 0);
    for (size_t f = 0; f < mesh.faces.size(); ++f) {
      const Face& t = mesh.faces[f];
      areas[components.of_face[f]] +=
          (mesh.positions[t[1]] - mesh.positions[t[0]])
              .cross(mesh.positions[t[2]] - mesh.positions[t[0]])
              .norm() /
          2;
    }
    return areas;
  }

  Status DropUnusableComponents(TriMesh& mesh) {
    const remesh::Components comps = remesh::LabelComponents(mesh);
    const std::vector<double> areas = ComponentAreas(mesh, comps);
    std::vector<uint32_t> faces(comps.count, 0);
    for (uint32_t c : comps.of_face) ++faces[c];
    const double diagonal = BoundingBox(mesh.positions).Diagonal();
    // "No area": below what float32 coordinates can resolve at this scale.
    const double min_area = 1e-14 * diagonal * diagonal;
    const auto tiny = static_cast<uint32_t>(options_.tiny_component_faces);
    std::vector<uint8_t> keep(comps.count, 1);
    size_t no_area = 0, dropped_tiny = 0;
    for (uint32_t c = 0; c < comps.count; ++c) {
      if (!(areas[c] > min_area)) {
        keep[c] = 0;
        ++no_area;
      } else if (faces[c] < tiny) {
        if (options_.drop_tiny_components) {
          keep[c] = 0;
          ++dropped_tiny;
        } else {
          ++result_.tiny_components;
        }
      }
    }
    const size_t dropped = no_area + dropped_tiny;
    if (dropped == comps.count) {
      return InvalidArgument(
          "nothing usable: " +
          (no_area == comps.count
               ? "every face left after cleaning (" +
                     std::to_string(mesh.faces.size()) +
                     ") has no area (its corners are collinear or coincide)"
               : "all " + std::to_string(comps.count) +
                     " components are tiny (fewer than " +
                     std::to_string(tiny) +
                     " faces) and dropping tiny components was asked for"));
    }
    if (no_area > 0) {
      Warn("dropped " + Count(no_area, "component", "components") +
           " without area (every face degenerate)");
    }
    if (dropped_tiny > 0) {
      Warn("dropped " + Count(dropped_tiny, "tiny component", "tiny components") +
           " (fewer than " + std::to_string(tiny) + " faces)");
    }
    if (result_.tiny_components > 0) {
      Warn("kept " +
           Count(result_.tiny_components, "tiny component", "tiny components") +
           " (fewer than " + std::to_string(tiny) +
           " faces), each as its own small base");
    }
    if (dropped > 0) {
      size_t dropped_faces = 0;
      for (uint32_t c = 0; c < comps.count; ++c) {
        if (!keep[c]) dropped_faces += faces[c];
      }
      result_.dropped_components = dropped;
      result_.dropped_faces = dropped_faces;
      mesh = KeepComponents(mesh, comps, keep);
    }
    result_.components = comps.count - dropped;
    return Status::Ok();
  }

  void AddResultWarnings(const remesh::FitStats& stats) {
    if (static_cast<double>(result_.base_faces) >
        1.25 * static_cast<double>(result_.target_base_faces)) {
      Warn("the base has " + std::to_string(result_.base_faces) +
           " faces, more than the " +
           std::to_string(result_.target_base_faces) +
           " planned: some components could not be simplified further "
           "without changing their topology or folding");
    }
    const double ratio = static_cast<double>(result_.finest_vertices) /
                         static_cast<double>(result_.input_vertices);
    if (options_.levels == -1 && options_.base_faces == -1 &&
        (ratio < 0.5 || ratio > 1.5)) {
      Warn("the finest level has " + std::to_string(result_.finest_vertices) +
           " vertices, far from the input's " +
           std::to_string(result_.input_vertices));
    }
    if (stats.unrepaired_faces > 0) {
      Warn(Count(stats.unrepaired_faces, "face", "faces") +
           " of the finest level stayed folded or degenerate after untangling");
    }
  }

  void Warn(std::string message) { result_.warnings.push_back(std::move(message)); }

  void Report(std::string_view stage, double fraction) {
    if (options_.progress) options_.progress(stage, fraction);
  }

  void EndStage(const char* name) {
    const Clock::time_point now = Clock::now();
    result_.stage_seconds.emplace_back(
        name, std::chrono::duration<double>(now - stage_start_).count());
    stage_start_ = now;
  }

  const RemeshOptions& options_;
  RemeshResult result_;
  Clock::time_point stage_start_;
};

}  // namespace

Result<RemeshResult> Remesh(const TriMesh& input,
                            const RemeshOptions& options) {
  Pipeline pipeline(options);
  return pipeline.Run(input);
}

}  // namespace meshwave
