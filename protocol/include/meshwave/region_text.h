// The text forms of a region (meshwave/region.h): what `meshwave fetch
// --region/--view/--screen-error` take and what the HTTP query and the
// WebSocket messages carry (docs/API.md). Safe on untrusted text: every
// refusal is a kInvalidArgument naming the field, the text quoted in a
// bounded, printable form.
#ifndef MESHWAVE_REGION_TEXT_H_
#define MESHWAVE_REGION_TEXT_H_

#include <string>
#include <string_view>

#include "meshwave/region.h"
#include "meshwave/status.h"

namespace meshwave {

// "x,y,z,r": a sphere. Finite numbers, r > 0; no spaces.
Result<Region> ParseSphereRegion(std::string_view text);
// "ex,ey,ez,dx,dy,dz,fov,width,height": a view; the direction is kept as
// given (not normalised, so that its text form reads back exactly), any
// length but zero; fov in degrees, in (0, 180); width and height
// whole numbers of pixels in [1, kMaxScreenPixels].
Result<Region> ParseViewRegion(std::string_view text);
// A screen-space error in pixels: a finite number > 0, at most
// kMaxScreenPixels.
Result<double> ParseScreenError(std::string_view text);
// ParseScreenError's checks on a number (a protobuf field, an option).
Result<double> CheckScreenError(double px);
// The text ParseScreenError reads back to `px` (shortest round trip).
std::string FormatScreenError(double px);
// The text form ParseSphereRegion or ParseViewRegion reads back to the same
// region (shortest round-tripping decimals).
std::string FormatRegionShape(const Region& region);

}  // namespace meshwave

#endif  // MESHWAVE_REGION_TEXT_H_
