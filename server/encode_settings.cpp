#include "encode_settings.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <string>

namespace meshwave::server {
namespace {

// The shortest text that reads back as the same double.
std::string Number(double v) {
  char buffer[32];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, r.ptr);
}

Result<double> ReadDouble(std::string_view key, std::string_view text, double lo, double hi) {
  double v = 0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (r.ec != std::errc() || r.ptr != text.data() + text.size() || !std::isfinite(v) || v < lo ||
      v > hi) {
    return InvalidArgument("encoder settings: " + std::string(key) + "=" + std::string(text) +
                           " is not a number in [" + Number(lo) + ", " + Number(hi) + "]");
  }
  return v;
}

Result<uint32_t> ReadCount(std::string_view key, std::string_view text) {
  uint32_t v = 0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (r.ec != std::errc() || r.ptr != text.data() + text.size() || text.empty()) {
    return InvalidArgument("encoder settings: " + std::string(key) + "=" + std::string(text) +
                           " is not a count");
  }
  return v;
}

}  // namespace

std::string FormatEncodeSettings(const EncodeChoices& c) {
  return "fidelity=" + Number(c.fidelity_db) + " max_vertex_ratio=" + Number(c.max_vertex_ratio) +
         " remesh=" + (c.force_remesh ? "always" : "auto") +
         " precinct=" + std::to_string(c.precinct_coefficients) +
         " split=" + std::to_string(c.split_bytes_per_precinct) +
         (c.original_layer ? "" : " original=no");
}

Result<EncodeChoices> ParseEncodeSettings(std::string_view text) {
  std::map<std::string, std::string, std::less<>> fields;
  size_t i = 0;
  while (i < text.size()) {
    const size_t end = std::min(text.find(' ', i), text.size());
    const std::string_view field = text.substr(i, end - i);
    const size_t eq = field.find('=');
    if (eq == std::string_view::npos || eq == 0) {
      return InvalidArgument("encoder settings: '" + std::string(field) + "' is not key=value");
    }
    if (!fields.emplace(field.substr(0, eq), field.substr(eq + 1)).second) {
      return InvalidArgument("encoder settings: " + std::string(field.substr(0, eq)) +
                             " given twice");
    }
    i = end + 1;
  }
  static constexpr std::string_view kKeys[] = {"fidelity", "max_vertex_ratio", "remesh",
                                               "precinct", "split"};
  // Keys a text may leave out: their defaults.
  static constexpr std::string_view kOptionalKeys[] = {"original"};
  for (const auto& [key, value] : fields) {
    if (std::find(std::begin(kKeys), std::end(kKeys), key) == std::end(kKeys) &&
        std::find(std::begin(kOptionalKeys), std::end(kOptionalKeys), key) ==
            std::end(kOptionalKeys)) {
      return InvalidArgument("encoder settings: unknown key '" + key + "'");
    }
  }
  for (std::string_view key : kKeys) {
    if (!fields.count(key)) {
      return InvalidArgument("encoder settings: " + std::string(key) + " missing");
    }
  }
  EncodeChoices c;
  MW_ASSIGN_OR_RETURN(c.fidelity_db, ReadDouble("fidelity", fields.find("fidelity")->second, 0, 200));
  MW_ASSIGN_OR_RETURN(c.max_vertex_ratio,
                      ReadDouble("max_vertex_ratio", fields.find("max_vertex_ratio")->second, 1, 64));
  const std::string& remesh = fields.find("remesh")->second;
  if (remesh != "auto" && remesh != "always") {
    return InvalidArgument("encoder settings: remesh=" + remesh + " (auto or always)");
  }
  c.force_remesh = remesh == "always";
  MW_ASSIGN_OR_RETURN(c.precinct_coefficients, ReadCount("precinct", fields.find("precinct")->second));
  MW_ASSIGN_OR_RETURN(c.split_bytes_per_precinct, ReadCount("split", fields.find("split")->second));
  if (const auto it = fields.find("original"); it != fields.end()) {
    if (it->second != "yes" && it->second != "no") {
      return InvalidArgument("encoder settings: original=" + it->second + " (yes or no)");
    }
    c.original_layer = it->second == "yes";
  }
  return c;
}

}  // namespace meshwave::server
