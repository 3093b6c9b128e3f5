#include "metrics/input_checks.h"

#include <cmath>
#include <string>

namespace meshwave::metrics {

Status CheckFinite(const std::vector<Vec3>& positions, std::string_view what) {
  for (size_t i = 0; i < positions.size(); ++i) {
    if (!positions[i].allFinite()) {
      return InvalidArgument(std::string(what) + ": vertex " +
                             std::to_string(i) +
                             " has a NaN or infinite coordinate");
    }
  }
  return Status::Ok();
}

Status CheckSurface(const TriMesh& mesh, std::string_view what) {
  if (mesh.faces.empty()) {
    return InvalidArgument(std::string(what) +
                           ": has no faces, so no surface to measure");
  }
  const size_t n = mesh.positions.size();
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    for (const uint32_t v : mesh.faces[f]) {
      if (v >= n) {
        return InvalidArgument(std::string(what) + ": face " +
                               std::to_string(f) + " refers to vertex " +
                               std::to_string(v) + " but there are only " +
                               std::to_string(n));
      }
    }
  }
  return CheckFinite(mesh.positions, what);
}

Status CheckPeak(double peak) {
  if (!std::isfinite(peak) || !(peak > 0)) {
    return InvalidArgument("PSNR peak must be finite and positive, got " +
                           std::to_string(peak));
  }
  return Status::Ok();
}

}  // namespace meshwave::metrics
