// The screen-space error the region-order and screen-error tests measure a
// view by (as `meshwave view-rd` does, with the test mesh's normals): the
// largest distance along the radial direction (the shared test mesh is a
// bumped sphere) between `got` and `full` over the vertices `camera` sees,
// in pixels at each vertex's depth.
#ifndef MESHWAVE_TESTS_CODEC_STREAM_SCREEN_ERROR_TESTONLY_H_
#define MESHWAVE_TESTS_CODEC_STREAM_SCREEN_ERROR_TESTONLY_H_

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "meshwave/mesh.h"
#include "meshwave/region.h"

namespace meshwave::testing {

inline double ScreenError(const ViewRegion& camera, const std::vector<Vec3>& full,
                          const std::vector<Vec3>& got) {
  const Vec3 forward = camera.direction.normalized();
  const Vec3 right = forward.cross(Vec3::UnitY()).normalized();
  const Vec3 up = right.cross(forward);
  const double tan_half = std::tan(camera.fov_degrees * std::numbers::pi / 360);
  double worst = 0;
  for (size_t v = 0; v < full.size(); ++v) {
    const Vec3 d = full[v] - camera.eye;
    const double z = d.dot(forward);
    if (z <= 0) continue;
    const double px = 0.5 * camera.height / (z * tan_half);
    if (std::abs(d.dot(right)) * px > 0.5 * camera.width ||
        std::abs(d.dot(up)) * px > 0.5 * camera.height) {
      continue;
    }
    worst = std::max(worst, std::abs((got[v] - full[v]).dot(full[v].normalized())) * px);
  }
  return worst;
}

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_CODEC_STREAM_SCREEN_ERROR_TESTONLY_H_
