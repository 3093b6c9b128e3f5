// Base64 (RFC 4648): the standard alphabet with padding for glTF data URIs,
// the URL-safe one without padding for what travels in a query string (a
// client's held units, docs/API.md).
#ifndef MESHWAVE_CORE_BASE64_H_
#define MESHWAVE_CORE_BASE64_H_

#include <optional>
#include <string>
#include <string_view>

namespace meshwave {

// Section 4: "+/" and "=" padding.
std::string Base64(std::string_view bytes);
// Section 5: "-_", no padding.
std::string Base64Url(std::string_view bytes);
// Section 5 without padding; nullopt for any other character, a length of
// 1 mod 4, or non-zero bits left over in the last digit.
std::optional<std::string> DecodeBase64Url(std::string_view text);

}  // namespace meshwave

#endif  // MESHWAVE_CORE_BASE64_H_
