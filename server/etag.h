// Strong entity tags for immutable resources and If-None-Match matching.
#ifndef MESHWAVE_SERVER_ETAG_H_
#define MESHWAVE_SERVER_ETAG_H_

#include <string>
#include <string_view>

namespace meshwave::server {

// "\"<sha256>-<variant>\"" (variant empty: the container itself). The
// content hash makes it change whenever the bytes could.
std::string StrongEtag(std::string_view sha256, std::string_view variant);

// True when an If-None-Match value ("*", or a list of tags, weak or not,
// compared weakly as RFC 9110 13.1.2 says) matches `etag`.
bool IfNoneMatchMatches(std::string_view header, std::string_view etag);

// The If-Range precondition (RFC 9110 13.1.5) for a resource whose strong
// tag is `etag` and that sends no Last-Modified: true only for the same
// entity-tag, compared strongly (a weak tag never matches). An HTTP-date is
// false, since without Last-Modified no date can validate ("MUST NOT" use
// it), and so is anything malformed: the Range is then ignored (200).
bool IfRangeHolds(std::string_view header, std::string_view etag);

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_ETAG_H_
