#include "meshwave/semiregular_input.h"

#include <utility>

#include "meshwave/fidelity.h"
#include "meshwave/mesh_clean.h"
#include "meshwave/remesh.h"
#include "meshwave/subdivision.h"

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
  RemeshResult remeshed;
  if (options.fidelity_db > 0) {
    MW_ASSIGN_OR_RETURN(FidelityRemesh fitted,
                        RemeshToFidelity(mesh, remesh, options.fidelity_db,
                                         options.max_vertex_ratio));
    remeshed = std::move(fitted.result);
    out.remesh_psnr_db = fitted.psnr_db;
    out.remesh_attempts = fitted.attempts;
  } else {
    MW_ASSIGN_OR_RETURN(remeshed, Remesh(mesh, remesh));
    out.remesh_attempts = 1;
  }
  out.remeshed = true;
  out.mesh = std::move(remeshed.mesh);
  out.levels = remeshed.levels;
  out.base_faces = remeshed.base_faces;
  out.finest_vertices = remeshed.finest_vertices;
  out.warnings = std::move(remeshed.warnings);
  return out;
}

}  // namespace meshwave
