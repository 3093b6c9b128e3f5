// Validation shared by the public metric functions, which accept meshes read
// from untrusted files.
#ifndef MESHWAVE_METRICS_INPUT_CHECKS_H_
#define MESHWAVE_METRICS_INPUT_CHECKS_H_

#include <string_view>
#include <vector>

#include "meshwave/mesh.h"
#include "meshwave/status.h"

namespace meshwave::metrics {

// InvalidArgument naming `what` and the first vertex with a NaN or infinite
// coordinate.
Status CheckFinite(const std::vector<Vec3>& positions, std::string_view what);

// CheckFinite, plus: at least one face, every face index in range.
Status CheckSurface(const TriMesh& mesh, std::string_view what);

// InvalidArgument unless `peak` is finite and positive.
Status CheckPeak(double peak);

}  // namespace meshwave::metrics

#endif  // MESHWAVE_METRICS_INPUT_CHECKS_H_
