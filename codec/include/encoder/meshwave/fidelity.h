// Fidelity: how close a complete stream comes to the mesh it was made from,
// as a user judges it: the symmetric surface distance to the original
// (`meshwave compare`), as a PSNR with the original's bounding-box diagonal
// as peak. `--fidelity DB` of `meshwave encode` and the server's ingest
// asks for one; the remesh density (SemiRegularInputOptions::fidelity_db)
// and the quantiser precision below are chosen for it.
#ifndef MESHWAVE_FIDELITY_H_
#define MESHWAVE_FIDELITY_H_

#include "meshwave/encoder.h"
#include "meshwave/mesh.h"
#include "meshwave/remesh.h"
#include "meshwave/status.h"

namespace meshwave {

// What `meshwave encode`, `remesh` and the server's ingest aim at when not
// told: Draco's default quantisation (`-qp 11`) lands at 82.6 to 84.0 dB on
// the shared meshes (docs/RD_RESULTS.md, "Fidelity"), and a user comparing
// the two expects at least that from a complete stream. The density this
// may take is bounded by kDefaultMaxVertexRatio finest vertices per input
// vertex (a mesh that needs more, e.g. a CAD part with sharp edges, gets the
// best remesh within it and a warning).
inline constexpr double kDefaultFidelityDb = 84;
inline constexpr double kDefaultMaxVertexRatio = 4;

// The EncodeOptions::precision whose quantisation error stays about 10 dB
// under `fidelity_db` (the complete stream's surface PSNR grows by about 6
// dB a bit of precision, from about 6 p + 12 dB), and never below the
// default 16.
int PrecisionForFidelity(double fidelity_db);

// A remesh as dense as a fidelity needs: Remesh(input, options), measured
// against the input (symmetric surface distance, 2 samples per face as
// `meshwave remesh` measures) and, while short of `fidelity_db`, redone
// denser, up to `max_vertex_ratio` finest vertices per input vertex:
// density from more levels first, the base taking the rest (0.76 to 3
// times the first attempt's), or from the base alone when options.levels
// is set; an attempt that overshoots by more than 2 dB
// is followed by one between it and the densest still short (6 attempts
// at most). Keeps the sparsest attempt that reaches the fidelity, else the
// best one. Never sparser than the default remesh.
struct FidelityRemesh {
  RemeshResult result;
  double psnr_db = 0;  // the kept attempt's, against the input
  int attempts = 0;
};
Result<FidelityRemesh> RemeshToFidelity(const TriMesh& input, RemeshOptions options,
                                        double fidelity_db, double max_vertex_ratio);

// The complete stream's symmetric surface PSNR against `original` (its
// original layer's mesh where it has one, else its finest level), on
// `threads` threads (0: the machine's cores; the same value for any count).
Result<double> CompleteStreamPsnr(const TriMesh& original, const EncodedStream& stream,
                                  int threads = 0);

}  // namespace meshwave

#endif  // MESHWAVE_FIDELITY_H_
