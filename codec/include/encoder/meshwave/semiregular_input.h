// Turning any triangle mesh into the semi-regular mesh an encoder needs:
// the mesh is used as it is when it already has subdivision connectivity,
// and remeshed otherwise. Shared by `meshwave encode` and the server's
// ingest so both treat a file alike.
#ifndef MESHWAVE_SEMIREGULAR_INPUT_H_
#define MESHWAVE_SEMIREGULAR_INPUT_H_

#include <string>
#include <vector>

#include "meshwave/fidelity.h"
#include "meshwave/mesh.h"
#include "meshwave/semiregular.h"
#include "meshwave/status.h"

namespace meshwave {

struct SemiRegularInputOptions {
  bool force_remesh = false;  // remesh even semi-regular input
  int levels = -1;            // remeshing levels (-1: chosen from the size)
  // Remeshing worker threads (0: the machine's cores); the result does not
  // depend on it.
  int threads = 0;
  // The remesh's symmetric surface PSNR against the input to reach, in dB
  // (peak: the input's bounding-box diagonal; what `meshwave compare`
  // reports): the remesh is measured and, while short of this, redone
  // denser (RemeshToFidelity), up to `max_vertex_ratio` times the input's
  // vertices. 0: remesh once at the first density (about as many finest
  // vertices as the input has).
  double fidelity_db = kDefaultFidelityDb;
  double max_vertex_ratio = kDefaultMaxVertexRatio;
};

struct SemiRegularInput {
  SemiRegularMesh mesh;
  bool remeshed = false;
  // Why the input was not used as it is (empty when it was).
  std::string not_semiregular_reason;
  int levels = 0;
  size_t base_faces = 0;
  size_t finest_vertices = 0;
  std::vector<std::string> warnings;  // from remeshing, one sentence each
  // With a fidelity asked for and the input remeshed: the remesh's surface
  // PSNR against the cleaned input, and how many remeshes it took.
  double remesh_psnr_db = 0;
  int remesh_attempts = 0;
};

// Cleans `mesh` (CleanMesh), detects a subdivision hierarchy and remeshes
// when there is none (or when asked), as densely as `fidelity_db` needs. Safe on untrusted meshes: errors are
// those of Remesh (kInvalidArgument naming what is unusable).
Result<SemiRegularInput> ToSemiRegular(TriMesh mesh,
                                       const SemiRegularInputOptions& options = {});

}  // namespace meshwave

#endif  // MESHWAVE_SEMIREGULAR_INPUT_H_
