// Untrusted text shown in an error message: the one rule for every message
// that quotes what a file or a client sent (mesh readers, region text,
// request parameters).
#ifndef MESHWAVE_CORE_QUOTED_H_
#define MESHWAVE_CORE_QUOTED_H_

#include <cstddef>
#include <string>
#include <string_view>

namespace meshwave {

// A token quoted for an error message: at most 40 characters, with bytes
// that are not printable ASCII shown as '?'.
inline std::string Quoted(std::string_view token) {
  constexpr size_t kMaxShown = 40;
  std::string out = "\"";
  for (size_t i = 0; i < token.size() && i < kMaxShown; ++i) {
    char c = token[i];
    out += (c >= 0x20 && c < 0x7f) ? c : '?';
  }
  if (token.size() > kMaxShown) out += "...";
  out += '"';
  return out;
}

}  // namespace meshwave

#endif  // MESHWAVE_CORE_QUOTED_H_
