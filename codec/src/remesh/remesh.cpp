// Remesh (meshwave/remesh.h): clean, repair, simplify, subdivide and fit.
#include "meshwave/remesh.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <tuple>
#include <utility>

#include "meshwave/mesh_clean.h"
#include "meshwave/mesh_stats.h"
#include "remesh/base_flips.h"
#include "remesh/coincident_vertices.h"
#include "remesh/components.h"
#include "remesh/fit_least_squares.h"
#include "remesh/fit_projection.h"
#include "remesh/input_surface.h"
#include "remesh/level_plan.h"
#include "remesh/manifold_repair.h"
#include "remesh/missed_features.h"
#include "remesh/qem_simplifier.h"
#include "remesh/remesh_quality.h"
#include "remesh/surface_fitting.h"
#include "semiregular/vertex_rings.h"

namespace meshwave {
namespace {

using Clock = std::chrono::steady_clock;

// Every component keeps at least this many base faces (all of its faces
// when it has fewer). With 8 (an octahedron), ogre's elongated claws came
// out half inside-out (RMS 24 % of the claw's own diagonal); with 16 they
// fit (0.7 %), with 24 a third of ogre's base went to its 40 small parts.
constexpr uint32_t kMinComponentBaseFaces = 16;

// Put-off collapses (qem_simplifier.h) may shrink a component only down to
// this multiple of its share of the base faces by input faces: small parts
// that cannot shrink cleanly (ogre's claws) still shrink, while no part is
// forced into folds below its share; the base may then exceed its target.
// On ogre.obj: 1.0 gives a base of 1,943 faces as planned, 2.0 one of
// 2,813 (finest level 1.45x the input, at the edge of the budget).
constexpr double kLateFloorShare = 1.0;

// Base edges longer than this many times the edge of an even base with the
// planned face count are made only when nothing else is left.
constexpr double kMaxBaseEdgeRatio = 3.0;

// Progress bar: repair up to kAttemptStart[0], the first simplification
// and fitting up to kAttemptStart[1], further ones (when features were
// missed) up to kCheckStart; simplification takes about half of each
// (igea.ply subdivided to 1 M faces).
constexpr double kAttemptStart[] = {0.05, 0.5, 0.75, 0.95};
constexpr int kMaxAttempts = 3;
constexpr double kCheckStart = 0.95;
constexpr double kSimplifyPart = 0.5;

// Retries (see FitBestAttempt): another attempt runs while the best result
// misses an input vertex by more than kAcceptableMiss of the diagonal; it keeps
// in the base the farthest vertex beyond kRefineThreshold of every
// kLockSpacing-wide neighbourhood (at most kMaxLockShare times the planned
// base faces of them, accumulated over attempts). Vertex misses of attempts
// 0 / 1 / 2 in % of the diagonal on the shared meshes: horse 0.56 / 0.59 /
// 0.44, fandisk 0.79 / 0.80 / 0.72, elephant_cartoon 0.56 / 0.61 / 0.41;
// ogre 0.72 / 1.18 / 1.12 (its thin parts move between caught and missed
// with any change of the base, so there the first attempt stays).
constexpr double kRefineThreshold = 0.0015;
constexpr double kAcceptableMiss = 0.005;
constexpr double kLockSpacing = 0.01;
constexpr double kMaxLockShare = 0.05;

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

  // The named steps below, in order; each ends its stage of
  // result_.stage_seconds and reports its progress.
  Result<RemeshResult> Run(const TriMesh& input) {
    const Clock::time_point start = Clock::now();
    stage_start_ = start;
    MW_RETURN_IF_ERROR(Validate(input));
    MW_ASSIGN_OR_RETURN(TriMesh mesh, Repair(input));
    MW_ASSIGN_OR_RETURN(const remesh::LevelPlan plan, Plan(mesh));
    remesh::Components components = remesh::LabelComponents(mesh);
    remesh::SimplifyOptions simplify =
        PlanSimplification(mesh, components, plan);
    simplify.threads = options_.threads;
    // The first simplification needs only the mesh; the surface the fit
    // queries (normals, BVH, boundary loops) is built beside its collapses
    // (its set-up takes every thread).
    std::unique_ptr<remesh::InputSurface> surface;
    remesh::SimplifyOptions first = simplify;
    first.beside = [&] {
      surface = std::make_unique<remesh::InputSurface>(TriMesh(mesh),
                                                       remesh::Components(components));
    };
    remesh::SimplifiedMesh first_base = Simplify(mesh, components, first, 0, "simplify");
    mesh = TriMesh{};
    components = remesh::Components{};
    EndStage("simplify");
    MW_ASSIGN_OR_RETURN(
        Attempt attempt,
        FitBestAttempt(*surface, plan, std::move(simplify), std::move(first_base)));
    Measure(*surface, std::move(attempt));
    AddResultWarnings();
    Report("done", 1);
    result_.seconds =
        std::chrono::duration<double>(Clock::now() - start).count();
    return std::move(result_);
  }

 private:
  // One simplification and fitting of the whole input.
  struct Attempt {
    SemiRegularMesh mesh;
    std::vector<remesh::SurfaceAnchor> anchors;
    remesh::FitStats stats;
    size_t base_vertices = 0;
    size_t base_faces = 0;
  };

  // The input's indices and coordinates, and the options, before any work.
  Status Validate(const TriMesh& input) const {
    MW_RETURN_IF_ERROR(CheckInput(input));
    return remesh::PlanLevels(input.positions.size(), options_.levels,
                              options_.base_faces)
        .status();
  }

  // Stage "repair": the input cleaned (CleanMesh), made an oriented
  // manifold (RepairManifold) and rid of components without area (and of
  // tiny ones if asked); what was done goes into result_ and its warnings.
  Result<TriMesh> Repair(const TriMesh& input) {
    TriMesh mesh = input;
    result_.cleaning = CleanMesh(mesh);
    if (mesh.faces.empty()) {
      return InvalidArgument(
          "nothing usable: all " + std::to_string(input.faces.size()) +
          " faces repeat a corner or duplicate another face");
    }
    Report("repair", 0);
    const remesh::RepairReport repair = remesh::RepairManifold(mesh, options_.threads);
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
    return mesh;
  }

  // Levels J and base faces N for the repaired input (level_plan.h).
  Result<remesh::LevelPlan> Plan(const TriMesh& mesh) {
    MW_ASSIGN_OR_RETURN(
        const remesh::LevelPlan plan,
        remesh::PlanLevels(mesh.positions.size(), options_.levels,
                           options_.base_faces));
    result_.levels = plan.levels;
    result_.target_base_faces = plan.base_faces;
    return plan;
  }

  // How far simplification may go: the planned base faces, a longest base
  // edge, and per component a floor of faces and a share for put-off
  // collapses.
  static remesh::SimplifyOptions PlanSimplification(
      const TriMesh& mesh, const remesh::Components& components,
      const remesh::LevelPlan& plan) {
    std::vector<uint32_t> faces_per_component(components.count, 0);
    for (uint32_t c : components.of_face) ++faces_per_component[c];
    remesh::SimplifyOptions simplify;
    simplify.target_faces = plan.base_faces;
    // Edges of an even base of equilateral triangles have length
    // sqrt(4 A / (√3 N)).
    {
      double area = 0;
      for (double a : ComponentAreas(mesh, components)) area += a;
      simplify.max_edge_length =
          kMaxBaseEdgeRatio *
          std::sqrt(4 * area /
                    (std::sqrt(3.0) * static_cast<double>(plan.base_faces)));
    }
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
    return simplify;
  }

  // Stages "simplify", "fit", "check features" and, when features were
  // missed, "refine": the first attempt; then, while the best result misses
  // some input vertex by more than kAcceptableMiss (a tip or corner that
  // simplification let go), another with the vertices farther than
  // kRefineThreshold found so far kept in the base. The best is kept:
  // within kAcceptableMiss of the diagonal, the one with fewer folds;
  // beyond, the nearer one. Small changes of the base move thin parts
  // (ogre's ear tips) between "caught" and "missed", so a single retry
  // can trade one miss for another; the locks accumulate.
  Result<Attempt> FitBestAttempt(const remesh::InputSurface& surface,
                                 const remesh::LevelPlan& plan,
                                 remesh::SimplifyOptions simplify,
                                 remesh::SimplifiedMesh first_base) {
    const double diagonal = surface.diagonal();
    const size_t max_locks =
        static_cast<size_t>(kMaxLockShare *
                            static_cast<double>(plan.base_faces)) +
        1;
    const auto measure = [&](const Attempt& a) {
      return remesh::FindMissedVertices(
          surface.mesh(), a.mesh.Finest(), kRefineThreshold * diagonal,
          kLockSpacing * diagonal, max_locks, options_.threads);
    };
    const auto score = [&](const remesh::MissedVertices& m, const Attempt& a) {
      const bool unacceptable = m.max_distance > kAcceptableMiss * diagonal;
      const double folds = static_cast<double>(a.stats.unrepaired_faces);
      return std::make_tuple(unacceptable,
                             unacceptable ? m.max_distance : folds,
                             unacceptable ? folds : m.max_distance);
    };
    MW_ASSIGN_OR_RETURN(Attempt attempt,
                        Fit(surface, std::move(first_base), simplify.locked, plan, 0, "fit"));
    remesh::MissedVertices missed = measure(attempt);
    EndStage("check features");
    auto best_score = score(missed, attempt);
    simplify.locked.assign(surface.mesh().positions.size(), 0);
    size_t locks = 0;
    for (int index = 1; index < kMaxAttempts && !missed.vertices.empty();
         ++index) {
      // Another attempt only while the best one is not acceptable.
      if (!std::get<0>(best_score)) break;
      for (uint32_t v : missed.vertices) {
        if (!simplify.locked[v]) ++locks;
        simplify.locked[v] = 1;
      }
      remesh::SimplifiedMesh base = Simplify(surface.mesh(), surface.components(),
                                             simplify, index, "refine");
      MW_ASSIGN_OR_RETURN(Attempt next, Fit(surface, std::move(base), simplify.locked,
                                            plan, index, "refine"));
      missed = measure(next);
      const auto next_score = score(missed, next);
      if (next_score < best_score) {
        best_score = next_score;
        attempt = std::move(next);
        result_.locked_features = locks;
      }
    }
    if (locks > 0) EndStage("refine");
    return attempt;
  }

  // Stage "check": keeps the attempt as the result and measures its finest
  // level against the input (MeasureQuality).
  void Measure(const remesh::InputSurface& surface, Attempt attempt) {
    result_.base_vertices = attempt.base_vertices;
    result_.base_faces = attempt.base_faces;
    result_.normal_hits = attempt.stats.normal_hits;
    result_.closest_fallbacks = attempt.stats.closest_fallbacks;
    result_.boundary_vertices = attempt.stats.boundary_vertices;
    result_.mesh = std::move(attempt.mesh);
    const std::vector<remesh::SurfaceAnchor> anchors =
        std::move(attempt.anchors);

    Report("check", kCheckStart);
    const TriMesh finest = result_.mesh.Finest();
    std::vector<uint32_t> face_component(finest.faces.size());
    for (size_t f = 0; f < finest.faces.size(); ++f) {
      face_component[f] = anchors[finest.faces[f][0]].component;
    }
    const remesh::QualityFigures quality = remesh::MeasureQuality(
        finest, face_component, surface, options_.threads);
    result_.flipped_faces = quality.flipped_faces;
    result_.degenerate_faces = quality.degenerate_faces;
    result_.min_angle_degrees = quality.min_angle_degrees;
    result_.finest_vertices = finest.positions.size();
    result_.finest_faces = finest.faces.size();
    EndStage("check");
  }

  // Progress: attempt i runs over [kAttemptStart[i], kAttemptStart[i + 1]),
  // its simplification the first kSimplifyPart of that.
  remesh::SimplifiedMesh Simplify(const TriMesh& mesh,
                                  const remesh::Components& components,
                                  const remesh::SimplifyOptions& options_in,
                                  int index, const char* stage) {
    const double begin = kAttemptStart[index];
    const double span = kAttemptStart[index + 1] - begin;
    remesh::SimplifyOptions options = options_in;
    options.progress = [this, begin, span, stage](double f) {
      Report(stage, begin + span * kSimplifyPart * f);
    };
    Report(stage, begin);
    remesh::SimplifiedMesh base =
        remesh::SimplifyByEdgeCollapse(mesh, components, options);
    remesh::FlipToImproveAngles(base.mesh);
    return base;
  }

  Result<Attempt> Fit(const remesh::InputSurface& surface,
                      remesh::SimplifiedMesh base,
                      const std::vector<uint8_t>& locked,
                      const remesh::LevelPlan& plan, int index,
                      const char* fit_stage) {
    const double begin = kAttemptStart[index];
    const double span = kAttemptStart[index + 1] - begin;
    auto hierarchy = SemiRegularHierarchy::Build(
        static_cast<uint32_t>(base.mesh.positions.size()), base.mesh.faces,
        plan.levels);
    if (!hierarchy.ok()) {
      return hierarchy.status().WithContext("building the remesh hierarchy");
    }
    Attempt out;
    out.base_vertices = base.mesh.positions.size();
    out.base_faces = base.mesh.faces.size();
    std::vector<Vec3> positions;
    remesh::PlaceBaseVertices(base, surface, locked, positions, out.anchors);
    remesh::FitOptions fit;
    fit.relax_rounds = options_.relax_rounds;
    fit.least_squares_rounds = options_.least_squares_rounds;
    fit.threads = options_.threads;
    fit.progress = [this, begin, span, fit_stage](int, double f) {
      Report(fit_stage,
             begin + span * (kSimplifyPart + (1 - kSimplifyPart) * f));
    };
    MW_RETURN_IF_ERROR(remesh::FitLevels(*hierarchy, surface, fit, positions,
                                         out.anchors, &out.stats)
                           .WithContext("fitting the remesh"));
    const bool least_squares = fit.least_squares_rounds > 0;
    if (least_squares) {
      if (index == 0) EndStage("fit");
      MW_ASSIGN_OR_RETURN(VertexRings rings,
                          VertexRings::Build((*hierarchy)->vertex_count(plan.levels),
                                             (*hierarchy)->faces(plan.levels)));
      const remesh::FitState state{**hierarchy, surface,     fit,
                                   positions,   out.anchors, out.stats};
      remesh::FitLeastSquares(state, rings);
    }
    out.mesh.hierarchy = *hierarchy;
    out.mesh.positions = std::move(positions);
    remesh::SeparateCoincidentVertices(out.mesh.positions,
                                       (*hierarchy)->faces(plan.levels));
    if (index == 0) EndStage(least_squares ? "least squares" : "fit");
    return out;
  }

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
      Warn("dropped " +
           Count(dropped_tiny, "tiny component", "tiny components") +
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

  void AddResultWarnings() {
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
    if (result_.flipped_faces + result_.degenerate_faces > 0) {
      Warn(Count(result_.flipped_faces, "face", "faces") +
           " of the finest level turned against the input and " +
           Count(result_.degenerate_faces, "face", "faces") +
           " without area stayed after untangling (thin parts narrower "
           "than an edge of the remesh, mostly)");
    }
  }

  void Warn(std::string message) {
    result_.warnings.push_back(std::move(message));
  }

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
