// A multipart/form-data request body (RFC 7578; the framing is RFC 2046,
// section 5.1.1): the parts of an upload of several files, as
// `curl -F mesh=@die.obj -F mtl=@die.mtl` sends them. The parser takes
// untrusted bytes: every malformed or truncated body gives a kParseError
// saying where, never a crash; parts are views into the body, so nothing
// is copied and nothing is sized by a count the body claims.
#ifndef MESHWAVE_SERVER_MULTIPART_FORM_H_
#define MESHWAVE_SERVER_MULTIPART_FORM_H_

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "meshwave/status.h"

namespace meshwave::server {

struct FormPart {
  std::string name;      // the form field (Content-Disposition name=)
  std::string filename;  // filename=, as sent; empty when the part has none
  std::string_view bytes;  // the part's content, a view into the body
};

// Bounds on a body's framing (its content is bounded by the body limit).
inline constexpr size_t kMaxFormParts = 64;
inline constexpr size_t kMaxFormPartHeaderBytes = 8192;

// Whether a Content-Type value is multipart/form-data (any case, any
// parameters).
bool IsMultipartFormData(std::string_view content_type);

// The boundary parameter of a multipart/form-data Content-Type value,
// unquoted. kParseError when it is missing or not 1 to 70 characters of
// RFC 2046's set.
Result<std::string> MultipartBoundary(std::string_view content_type);

// The parts of `body` framed by `boundary`, in order. A preamble before
// the first delimiter and an epilogue after the last are ignored. Each part
// needs a Content-Disposition: form-data header with a name; its other
// headers are ignored. kParseError for a body without the closing
// delimiter (truncated), a part without its blank line after the headers,
// headers over kMaxFormPartHeaderBytes, more than `max_parts` parts, a
// missing or malformed Content-Disposition, or no part at all.
Result<std::vector<FormPart>> ParseMultipartForm(std::string_view body, std::string_view boundary,
                                                 size_t max_parts = kMaxFormParts);

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_MULTIPART_FORM_H_
