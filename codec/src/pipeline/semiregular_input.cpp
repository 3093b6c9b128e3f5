#include "meshwave/semiregular_input.h"

#include <utility>

#include "meshwave/remesh.h"

namespace meshwave {

Result<SemiRegularInput> ToSemiRegular(TriMesh mesh,
                                       const SemiRegularInputOptions& options) {
  CleanMesh(mesh);
  SemiRegularInput out;
  if (!options.force_remesh) {
    auto detected = DetectSemiRegular(mesh);
    if (detected.ok()) {
      out.mesh = std::move(detected->mesh);
      out.levels = out.mesh.levels();
      out.base_faces = out.mesh.hierarchy->faces(0).size();
      out.finest_vertices = out.mesh.hierarchy->vertex_count(out.levels);
      return out;
    }
    out.not_semiregular_reason = detected.status().message();
  } else {
    out.not_semiregular_reason = "remeshing was asked for";
  }
  RemeshOptions remesh;
  remesh.levels = options.levels;
  remesh.threads = options.threads;
  MW_ASSIGN_OR_RETURN(RemeshResult remeshed, Remesh(mesh, remesh));
  out.remeshed = true;
  out.mesh = std::move(remeshed.mesh);
  out.levels = remeshed.levels;
  out.base_faces = remeshed.base_faces;
  out.finest_vertices = remeshed.finest_vertices;
  out.warnings = std::move(remeshed.warnings);
  return out;
}

}  // namespace meshwave
