// How much a part of the mesh matters to a region (meshwave/region.h).
#include "meshwave/region.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace meshwave {

double RegionWeight(const Region& region, const Vec3& centre, double radius) {
  radius = std::max(radius, 0.0);
  if (const auto* s = std::get_if<SphereRegion>(&region.shape)) {
    const double gap = (centre - s->centre).norm() - s->radius - radius;
    if (gap <= 0) return 1;
    const double g = gap / s->radius;
    return 1 / (1 + g * g);
  }
  const auto& v = std::get<ViewRegion>(region.shape);
  const Vec3 to = centre - v.eye;
  const double distance = to.norm();
  if (distance <= radius) return 1;
  const double half = v.fov_degrees * std::numbers::pi / 360;
  const double tan_half = std::tan(half);
  const double aspect =
      static_cast<double>(v.width) / static_cast<double>(v.height);
  // The cone through the screen's corners, widened by the ball's angular
  // radius.
  const double cone = std::atan(tan_half * std::sqrt(1 + aspect * aspect));
  const double along = to.dot(v.direction) / (v.direction.norm() * distance);
  const double angle = std::acos(std::clamp(along, -1.0, 1.0));
  const double angular_radius = std::asin(std::min(1.0, radius / distance));
  if (angle - angular_radius > cone) return 0;
  return std::min(1.0, radius / (distance * tan_half));
}

double PixelsPerUnit(const ViewRegion& view, const Vec3& centre,
                     double radius) {
  const double depth = (centre - view.eye).dot(view.direction.normalized()) -
                       std::max(radius, 0.0);
  if (!(depth > 0)) return std::numeric_limits<double>::infinity();
  const double tan_half = std::tan(view.fov_degrees * std::numbers::pi / 360);
  return 0.5 * static_cast<double>(view.height) / (depth * tan_half);
}

}  // namespace meshwave
