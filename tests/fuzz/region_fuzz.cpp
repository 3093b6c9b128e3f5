// Fuzz target: the region parameters a client sends (meshwave/region.h),
// as the HTTP query and the WebSocket messages carry them. The first byte
// picks the parser; a region that parses must format to text that parses
// back to it, weigh every ball in [0, 1] and, for a view, give every ball
// a scale that is a number of pixels per unit length or +infinity.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>
#include <variant>

#include "meshwave/region_text.h"

namespace {

void Check(bool ok) {
  if (!ok) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  using namespace meshwave;
  const std::string_view text(reinterpret_cast<const char*>(data) + 1, size - 1);
  Result<Region> region = InvalidArgument("");
  switch (data[0] % 3) {
    case 0: region = ParseSphereRegion(text); break;
    case 1: region = ParseViewRegion(text); break;
    default: {
      auto px = ParseScreenError(text);
      if (px.ok()) Check(*px > 0 && *px <= kMaxScreenPixels);
      return 0;
    }
  }
  if (!region.ok()) return 0;
  const std::string formatted = FormatRegionShape(*region);
  auto again = data[0] % 3 == 0 ? ParseSphereRegion(formatted) : ParseViewRegion(formatted);
  Check(again.ok());
  Check(*again == *region);
  for (const Vec3& c : {Vec3(0, 0, 0), Vec3(1, 2, 3), Vec3(-1e6, 0, 1e6)}) {
    for (double r : {0.0, 1e-9, 1.0, 1e12}) {
      const double w = RegionWeight(*region, c, r);
      Check(std::isfinite(w) && w >= 0 && w <= 1);
      // A view's scale for screen-space errors: a number of pixels per unit
      // length, +infinity where the ball reaches the eye's plane.
      if (const auto* view = std::get_if<ViewRegion>(&region->shape)) {
        const double px = PixelsPerUnit(*view, c, r);
        Check(!std::isnan(px) && px >= 0);
      }
    }
  }
  return 0;
}
