// Turning any triangle mesh into the semi-regular mesh an encoder needs:
// the mesh is used as it is when it already has subdivision connectivity,
// and remeshed otherwise. Shared by `meshwave encode` and the server's
// ingest so both treat a file alike.
#ifndef MESHWAVE_SEMIREGULAR_INPUT_H_
#define MESHWAVE_SEMIREGULAR_INPUT_H_

#include <string>
#include <vector>

#include "meshwave/mesh.h"
#include "meshwave/semiregular.h"
#include "meshwave/status.h"

namespace meshwave {

struct SemiRegularInputOptions {
  bool force_remesh = false;  // remesh even semi-regular input
  int levels = -1;            // remeshing levels (-1: chosen from the size)
  int threads = 2;            // remeshing worker threads
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
};

// Cleans `mesh` (CleanMesh), detects a subdivision hierarchy and remeshes
// when there is none (or when asked). Safe on untrusted meshes: errors are
// those of Remesh (kInvalidArgument naming what is unusable).
Result<SemiRegularInput> ToSemiRegular(TriMesh mesh,
                                       const SemiRegularInputOptions& options = {});

}  // namespace meshwave

#endif  // MESHWAVE_SEMIREGULAR_INPUT_H_
