// Parsing of an untrusted request target ("/v1/meshes/abc?x=1") into
// percent-decoded path segments and query parameters. Traversal attempts
// ("..", "%2e%2e", encoded slashes), control bytes and malformed escapes
// are refused here, before any handler sees the path.
#ifndef MESHWAVE_REQUEST_TARGET_H_
#define MESHWAVE_REQUEST_TARGET_H_

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "meshwave/status.h"

namespace meshwave {

inline constexpr size_t kMaxTargetLength = 2048;

class QueryParams {
 public:
  // The value of `key`, or nullopt.
  std::optional<std::string> Get(std::string_view key) const;
  // kInvalidArgument naming the first key not in `allowed`.
  Status CheckAllowed(std::initializer_list<std::string_view> allowed) const;
  bool empty() const { return params_.empty(); }

 private:
  friend Result<struct RequestTarget> ParseRequestTarget(std::string_view target);
  std::vector<std::pair<std::string, std::string>> params_;
};

struct RequestTarget {
  std::vector<std::string> segments;  // "/v1/meshes" -> {"v1", "meshes"}
  QueryParams query;
};

// Origin-form targets only ("/path?query"), at most kMaxTargetLength bytes.
// kInvalidArgument for: no leading '/', a fragment, bad or NUL escapes,
// empty, "." or ".." segments (also when encoded), encoded '/' or '\\',
// bytes outside the URL character set, a repeated query key.
Result<RequestTarget> ParseRequestTarget(std::string_view target);

// A decimal integer in [0, max]: digits only (no sign, no spaces).
// kInvalidArgument naming `what` otherwise, including overflow.
Result<uint64_t> ParseUnsigned(std::string_view text, uint64_t max,
                               std::string_view what);

}  // namespace meshwave

#endif  // MESHWAVE_REQUEST_TARGET_H_
