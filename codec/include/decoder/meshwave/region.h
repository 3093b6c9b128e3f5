// A region of interest a client asks the server to refine first: a sphere
// or a view (camera, direction, field of view, screen size), optionally with
// the screen-space error below which a view needs no more detail, and how
// much a part of the mesh matters to it. Its text forms, which requests
// carry: meshwave/region_text.h.
#ifndef MESHWAVE_REGION_H_
#define MESHWAVE_REGION_H_

#include <cstdint>
#include <optional>
#include <variant>

#include "meshwave/mesh.h"

namespace meshwave {

// Everything within `radius` of `centre`.
struct SphereRegion {
  Vec3 centre = Vec3::Zero();
  double radius = 0;  // > 0
  bool operator==(const SphereRegion&) const = default;
};

// What a perspective camera at `eye` looking along `direction` sees on a
// screen of width x height pixels with a vertical field of view of
// `fov_degrees`.
struct ViewRegion {
  Vec3 eye = Vec3::Zero();
  Vec3 direction = Vec3::UnitZ();  // not zero; any length
  double fov_degrees = 60;         // in (0, 180)
  uint32_t width = 1;              // pixels, [1, kMaxScreenPixels]
  uint32_t height = 1;
  bool operator==(const ViewRegion&) const = default;
};

inline constexpr uint32_t kMaxScreenPixels = 16384;
// Coordinates and radii beyond this magnitude are refused (meshes are
// quantised far below it; it keeps every product finite).
inline constexpr double kMaxRegionCoordinate = 1e15;

struct Region {
  std::variant<SphereRegion, ViewRegion> shape;
  // Pixels of projected error below which a part of the view is fine
  // (views only).
  std::optional<double> screen_error_px;
  bool operator==(const Region&) const = default;
};

// How much a ball (a part of the mesh, centre and bounding radius) matters
// to the region, in [0, 1]. A sphere: 1 for a ball that meets it, else
// 1 / (1 + (gap / sphere radius)^2) with the gap between them. A view: 1
// when the eye is inside the ball; 0 when the ball is wholly behind the
// camera or outside the cone around the screen's corners; else the ball's
// projected radius over the screen's half height (r / (d tan(fov / 2)) at
// distance d), capped at 1.
double RegionWeight(const Region& region, const Vec3& centre, double radius);

// How many pixels a length of 1 spans on the view's screen at the ball's
// nearest depth along the view direction: (height / 2) / (depth tan(fov /
// 2)). +infinity when the ball reaches the plane of the eye (a part that
// close needs every detail). What a screen-space error request
// (Region::screen_error_px) scales each part's error bound by.
double PixelsPerUnit(const ViewRegion& view, const Vec3& centre, double radius);

}  // namespace meshwave

#endif  // MESHWAVE_REGION_H_
