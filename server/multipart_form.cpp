#include "multipart_form.h"

#include <algorithm>
#include <cctype>
#include <utility>

namespace meshwave::server {
namespace {

constexpr size_t kMaxBoundaryLength = 70;  // RFC 2046, section 5.1.1

bool EqualsIgnoreCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(a[i])) !=
        std::tolower(static_cast<unsigned char>(b[i]))) {
      return false;
    }
  }
  return true;
}

std::string_view Trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// RFC 2046's bcharsnospace, and the space (not last).
bool IsBoundaryChar(char c) {
  if (std::isalnum(static_cast<unsigned char>(c))) return true;
  switch (c) {
    case '\'': case '(': case ')': case '+': case '_': case ',': case '-':
    case '.': case '/': case ':': case '=': case '?': case ' ':
      return true;
    default:
      return false;
  }
}

// A name or filename for a message: at most 80 bytes, control bytes shown
// as '?'.
std::string Shown(std::string_view s) {
  std::string out(s.substr(0, 80));
  for (char& c : out) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  }
  return s.size() > 80 ? out + "..." : out;
}

// Parameters of a header value ("type; a=b; c=\"d\""), the first element
// apart. Quoted strings may hold ';' and backslash-escaped characters.
struct HeaderValue {
  std::string_view type;
  std::vector<std::pair<std::string, std::string>> params;
};

Result<HeaderValue> ParseHeaderValue(std::string_view value, std::string_view what) {
  HeaderValue out;
  size_t i = value.find(';');
  out.type = Trim(value.substr(0, i));
  while (i != std::string_view::npos && i < value.size()) {
    ++i;  // past ';'
    while (i < value.size() && (value[i] == ' ' || value[i] == '\t')) ++i;
    if (i == value.size()) break;  // a trailing ';'
    const size_t eq = value.find('=', i);
    if (eq == std::string_view::npos) {
      return ParseError(std::string(what) + ": parameter '" + Shown(value.substr(i)) +
                        "' has no value");
    }
    std::string key(Trim(value.substr(i, eq - i)));
    for (char& c : key) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    i = eq + 1;
    while (i < value.size() && (value[i] == ' ' || value[i] == '\t')) ++i;
    std::string text;
    if (i < value.size() && value[i] == '"') {
      ++i;
      bool closed = false;
      while (i < value.size()) {
        const char c = value[i++];
        if (c == '"') {
          closed = true;
          break;
        }
        if (c == '\\' && i < value.size()) {
          text += value[i++];
        } else {
          text += c;
        }
      }
      if (!closed) {
        return ParseError(std::string(what) + ": the quoted value of '" + Shown(key) +
                          "' is not closed");
      }
      while (i < value.size() && (value[i] == ' ' || value[i] == '\t')) ++i;
      if (i < value.size() && value[i] != ';') {
        return ParseError(std::string(what) + ": text after the quoted value of '" + Shown(key) +
                          "'");
      }
    } else {
      const size_t end = value.find(';', i);
      text = std::string(Trim(value.substr(i, end == std::string_view::npos ? end : end - i)));
      i = end == std::string_view::npos ? value.size() : end;
    }
    out.params.emplace_back(std::move(key), std::move(text));
    if (i < value.size() && value[i] != ';') break;
  }
  return out;
}

const std::string* Param(const HeaderValue& v, std::string_view key) {
  const std::string* found = nullptr;
  for (const auto& [k, value] : v.params) {
    if (k == key) found = &value;
  }
  return found;
}

// The headers of part `index` (1-based, for messages): its name and
// filename from Content-Disposition.
Status ParsePartHeaders(std::string_view headers, size_t index, FormPart& part) {
  const std::string where = "multipart part " + std::to_string(index);
  bool disposition = false;
  while (!headers.empty()) {
    const size_t end = headers.find("\r\n");
    const std::string_view line = headers.substr(0, end);
    headers = end == std::string_view::npos ? std::string_view() : headers.substr(end + 2);
    if (line.empty()) continue;
    if (line.front() == ' ' || line.front() == '\t') {
      return ParseError(where + ": folded header lines are not accepted");
    }
    const size_t colon = line.find(':');
    if (colon == std::string_view::npos || colon == 0) {
      return ParseError(where + ": header line '" + Shown(line) + "' has no name");
    }
    if (!EqualsIgnoreCase(Trim(line.substr(0, colon)), "content-disposition")) continue;
    if (disposition) return ParseError(where + ": two Content-Disposition headers");
    disposition = true;
    MW_ASSIGN_OR_RETURN(HeaderValue value,
                        ParseHeaderValue(line.substr(colon + 1), where + " Content-Disposition"));
    if (!EqualsIgnoreCase(value.type, "form-data")) {
      return ParseError(where + ": Content-Disposition is '" + Shown(value.type) +
                        "', not form-data");
    }
    const std::string* name = Param(value, "name");
    if (!name || name->empty()) {
      return ParseError(where + ": Content-Disposition has no name");
    }
    part.name = *name;
    if (const std::string* filename = Param(value, "filename")) part.filename = *filename;
  }
  if (!disposition) return ParseError(where + ": no Content-Disposition header");
  return Status::Ok();
}

}  // namespace

bool IsMultipartFormData(std::string_view content_type) {
  const std::string_view type = Trim(content_type.substr(0, content_type.find(';')));
  return EqualsIgnoreCase(type, "multipart/form-data");
}

Result<std::string> MultipartBoundary(std::string_view content_type) {
  MW_ASSIGN_OR_RETURN(HeaderValue value, ParseHeaderValue(content_type, "Content-Type"));
  const std::string* boundary = Param(value, "boundary");
  if (!boundary) return ParseError("Content-Type multipart/form-data has no boundary");
  if (boundary->empty() || boundary->size() > kMaxBoundaryLength || boundary->back() == ' ') {
    return ParseError("the multipart boundary must have 1 to 70 characters (not ending in a space)");
  }
  for (char c : *boundary) {
    if (!IsBoundaryChar(c)) {
      return ParseError("the multipart boundary holds a character RFC 2046 does not allow");
    }
  }
  return *boundary;
}

Result<std::vector<FormPart>> ParseMultipartForm(std::string_view body, std::string_view boundary,
                                                 size_t max_parts) {
  if (boundary.empty()) return ParseError("the multipart boundary is empty");
  const std::string dash = "--" + std::string(boundary);
  const std::string delimiter = "\r\n" + dash;
  // The first delimiter: at the start, or after a preamble.
  size_t pos = 0;
  if (!body.starts_with(dash)) {
    pos = body.find(delimiter);
    if (pos == std::string_view::npos) {
      return ParseError("the multipart body holds no boundary line ('" + Shown(dash) + "')");
    }
    pos += 2;
  }
  std::vector<FormPart> parts;
  while (true) {
    pos += dash.size();
    if (body.substr(pos, 2) == "--") break;  // the close delimiter
    while (pos < body.size() && (body[pos] == ' ' || body[pos] == '\t')) ++pos;
    if (body.size() - pos < 2) {
      return ParseError("the multipart body is truncated after a boundary line (no closing '" +
                        Shown(dash) + "--')");
    }
    if (body.substr(pos, 2) != "\r\n") {
      return ParseError("a multipart boundary line is followed by other text than a line end");
    }
    pos += 2;
    const size_t index = parts.size() + 1;
    if (parts.size() == max_parts) {
      return ParseError("the multipart body has more than " + std::to_string(max_parts) +
                        " parts");
    }
    // Headers, up to the blank line.
    size_t headers_end;
    size_t content;
    if (body.substr(pos, 2) == "\r\n") {
      headers_end = pos;
      content = pos + 2;
    } else {
      const size_t window = std::min(body.size() - pos, kMaxFormPartHeaderBytes + 4);
      const size_t blank = body.substr(pos, window).find("\r\n\r\n");
      if (blank == std::string_view::npos) {
        if (window > kMaxFormPartHeaderBytes) {
          return ParseError("multipart part " + std::to_string(index) + ": headers over " +
                            std::to_string(kMaxFormPartHeaderBytes) + " bytes");
        }
        return ParseError("multipart part " + std::to_string(index) +
                          ": the body ends inside its headers (truncated)");
      }
      headers_end = pos + blank;
      content = headers_end + 4;
    }
    FormPart part;
    MW_RETURN_IF_ERROR(ParsePartHeaders(body.substr(pos, headers_end - pos), index, part));
    const size_t next = body.find(delimiter, content);
    if (next == std::string_view::npos) {
      return ParseError("multipart part " + std::to_string(index) + " ('" + Shown(part.name) +
                        "') is not closed by a boundary line: the body is truncated");
    }
    part.bytes = body.substr(content, next - content);
    parts.push_back(std::move(part));
    pos = next + 2;
  }
  if (parts.empty()) return ParseError("the multipart body has no parts");
  return parts;
}

}  // namespace meshwave::server
