#include "meshwave/region_text.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <system_error>

#include "core/quoted.h"  // untrusted text in a message

namespace meshwave {
namespace {

// Splits `text` at commas into exactly N non-empty fields.
template <size_t N>
Result<std::array<std::string_view, N>> Fields(std::string_view text, const char* what) {
  std::array<std::string_view, N> out;
  size_t start = 0;
  for (size_t k = 0; k < N; ++k) {
    const size_t comma = text.find(',', start);
    const bool last = k + 1 == N;
    if (last != (comma == std::string_view::npos)) {
      return InvalidArgument(std::string(what) + " needs exactly " + std::to_string(N) +
                             " comma-separated numbers");
    }
    out[k] = text.substr(start, last ? std::string_view::npos : comma - start);
    if (out[k].empty()) return InvalidArgument(std::string(what) + ": an empty number");
    start = comma + 1;
  }
  return out;
}

Result<double> Number(std::string_view token, const char* what) {
  double v = 0;
  const char* end = token.data() + token.size();
  // from_chars takes no leading '+' and no spaces; both are refused here.
  auto [ptr, ec] = std::from_chars(token.data(), end, v);
  if (ec != std::errc() || ptr != end || !std::isfinite(v)) {
    return InvalidArgument(std::string(what) + ": " + Quoted(token) + " is not a finite number");
  }
  if (std::abs(v) > kMaxRegionCoordinate) {
    return InvalidArgument(std::string(what) + ": " + Quoted(token) + " is out of range");
  }
  return v;
}

Result<uint32_t> Pixels(std::string_view token, const char* what) {
  uint32_t v = 0;
  const char* end = token.data() + token.size();
  auto [ptr, ec] = std::from_chars(token.data(), end, v);
  if (ec != std::errc() || ptr != end || v < 1 || v > kMaxScreenPixels) {
    return InvalidArgument(std::string(what) + " must be a whole number of pixels in [1, " +
                           std::to_string(kMaxScreenPixels) + "]");
  }
  return v;
}

std::string Shortest(double v) {
  char buffer[32];
  auto [ptr, ec] = std::to_chars(buffer, buffer + sizeof(buffer), v);
  return ec == std::errc() ? std::string(buffer, ptr) : std::string("0");
}

}  // namespace

Result<Region> ParseSphereRegion(std::string_view text) {
  MW_ASSIGN_OR_RETURN(auto f, Fields<4>(text, "region"));
  SphereRegion s;
  for (int a = 0; a < 3; ++a) {
    MW_ASSIGN_OR_RETURN(s.centre[a], Number(f[static_cast<size_t>(a)], "region centre"));
  }
  MW_ASSIGN_OR_RETURN(s.radius, Number(f[3], "region radius"));
  if (!(s.radius > 0)) return InvalidArgument("region radius must be > 0");
  return Region{s, std::nullopt};
}

Result<Region> ParseViewRegion(std::string_view text) {
  MW_ASSIGN_OR_RETURN(auto f, Fields<9>(text, "view"));
  ViewRegion v;
  for (int a = 0; a < 3; ++a) {
    MW_ASSIGN_OR_RETURN(v.eye[a], Number(f[static_cast<size_t>(a)], "view eye"));
    MW_ASSIGN_OR_RETURN(v.direction[a], Number(f[static_cast<size_t>(a) + 3], "view direction"));
  }
  const double length = v.direction.norm();
  if (!(length > 0) || !std::isfinite(length)) {
    return InvalidArgument("view direction must not be zero");
  }
  MW_ASSIGN_OR_RETURN(v.fov_degrees, Number(f[6], "view field of view"));
  if (!(v.fov_degrees > 0 && v.fov_degrees < 180)) {
    return InvalidArgument("view field of view must be in (0, 180) degrees");
  }
  MW_ASSIGN_OR_RETURN(v.width, Pixels(f[7], "view width"));
  MW_ASSIGN_OR_RETURN(v.height, Pixels(f[8], "view height"));
  return Region{v, std::nullopt};
}

Result<double> ParseScreenError(std::string_view text) {
  MW_ASSIGN_OR_RETURN(double px, Number(text, "screen error"));
  return CheckScreenError(px);
}

Result<double> CheckScreenError(double px) {
  if (!(px > 0 && px <= kMaxScreenPixels)) {
    return InvalidArgument("screen error must be in (0, " + std::to_string(kMaxScreenPixels) +
                           "] pixels");
  }
  return px;
}

std::string FormatScreenError(double px) { return Shortest(px); }

std::string FormatRegionShape(const Region& region) {
  std::string out;
  const auto add = [&out](const std::string& field) {
    if (!out.empty()) out += ',';
    out += field;
  };
  if (const auto* s = std::get_if<SphereRegion>(&region.shape)) {
    for (int a = 0; a < 3; ++a) add(Shortest(s->centre[a]));
    add(Shortest(s->radius));
  } else {
    const auto& v = std::get<ViewRegion>(region.shape);
    for (int a = 0; a < 3; ++a) add(Shortest(v.eye[a]));
    for (int a = 0; a < 3; ++a) add(Shortest(v.direction[a]));
    add(Shortest(v.fov_degrees));
    add(std::to_string(v.width));
    add(std::to_string(v.height));
  }
  return out;
}

}  // namespace meshwave
