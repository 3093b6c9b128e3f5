#include "meshwave/request_target.h"

#include <algorithm>

namespace meshwave {
namespace {

int HexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// RFC 3986 pchar (minus '%', handled apart) plus '/', '?' for queries.
bool IsUrlChar(char c) {
  if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9')) {
    return true;
  }
  return std::string_view("-._~!$&'()*+,;=:@/?").find(c) != std::string_view::npos;
}

Result<std::string> Decode(std::string_view s, bool plus_is_space) {
  std::string out;
  out.reserve(s.size());
  for (size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (c == '%') {
      if (i + 2 >= s.size()) {
        return InvalidArgument("truncated percent escape");
      }
      const int hi = HexValue(s[i + 1]), lo = HexValue(s[i + 2]);
      if (hi < 0 || lo < 0) return InvalidArgument("malformed percent escape");
      const char d = static_cast<char>(hi * 16 + lo);
      if (d == '\0') return InvalidArgument("encoded NUL in the target");
      if (static_cast<unsigned char>(d) < 0x20 || d == 0x7f) {
        return InvalidArgument("encoded control character in the target");
      }
      out.push_back(d);
      i += 2;
    } else if (c == '+' && plus_is_space) {
      out.push_back(' ');
    } else {
      out.push_back(c);
    }
  }
  return out;
}

}  // namespace

std::optional<std::string> QueryParams::Get(std::string_view key) const {
  for (const auto& [k, v] : params_) {
    if (k == key) return v;
  }
  return std::nullopt;
}

Status QueryParams::CheckAllowed(std::initializer_list<std::string_view> allowed) const {
  for (const auto& [k, v] : params_) {
    if (std::find(allowed.begin(), allowed.end(), k) == allowed.end()) {
      return InvalidArgument("unknown query parameter '" + k + "'");
    }
  }
  return Status::Ok();
}

Result<RequestTarget> ParseRequestTarget(std::string_view target) {
  if (target.empty() || target[0] != '/') {
    return InvalidArgument("the request target must start with '/'");
  }
  if (target.size() > kMaxTargetLength) {
    return InvalidArgument("the request target is longer than " +
                           std::to_string(kMaxTargetLength) + " bytes");
  }
  for (char c : target) {
    if (c != '%' && !IsUrlChar(c)) {
      return InvalidArgument("the request target holds a character outside the URL set");
    }
  }
  RequestTarget out;
  const size_t q = target.find('?');
  std::string_view path = target.substr(0, q);
  const std::string_view query = q == std::string_view::npos ? "" : target.substr(q + 1);

  path.remove_prefix(1);
  while (!path.empty()) {
    const size_t slash = path.find('/');
    const std::string_view raw = path.substr(0, slash);
    path = slash == std::string_view::npos ? "" : path.substr(slash + 1);
    if (raw.empty()) return InvalidArgument("empty path segment");
    MW_ASSIGN_OR_RETURN(std::string seg, Decode(raw, false));
    if (seg == "." || seg == "..") return InvalidArgument("'.' or '..' path segment");
    if (seg.find_first_of("/\\") != std::string::npos) {
      return InvalidArgument("encoded '/' or '\\' in a path segment");
    }
    out.segments.push_back(std::move(seg));
    if (slash != std::string_view::npos && path.empty()) {
      return InvalidArgument("empty path segment");  // trailing '/'
    }
  }

  std::string_view rest = query;
  while (!rest.empty()) {
    const size_t amp = rest.find('&');
    const std::string_view pair = rest.substr(0, amp);
    rest = amp == std::string_view::npos ? "" : rest.substr(amp + 1);
    if (pair.empty()) continue;
    const size_t eq = pair.find('=');
    MW_ASSIGN_OR_RETURN(std::string key, Decode(pair.substr(0, eq), true));
    std::string value;
    if (eq != std::string_view::npos) {
      MW_ASSIGN_OR_RETURN(value, Decode(pair.substr(eq + 1), true));
    }
    if (key.empty()) return InvalidArgument("empty query parameter name");
    if (out.query.Get(key)) {
      return InvalidArgument("query parameter '" + key + "' given twice");
    }
    out.query.params_.emplace_back(std::move(key), std::move(value));
  }
  return out;
}

Result<uint64_t> ParseUnsigned(std::string_view text, uint64_t max, std::string_view what) {
  const std::string name(what);
  if (text.empty()) return InvalidArgument(name + " is empty");
  uint64_t v = 0;
  for (char c : text) {
    if (c < '0' || c > '9') {
      return InvalidArgument(name + " must be a non-negative decimal integer");
    }
    const uint64_t d = static_cast<uint64_t>(c - '0');
    if (v > max / 10 || d > max - v * 10) return InvalidArgument(name + " is larger than " + std::to_string(max));
    v = v * 10 + d;
  }
  return v;
}

}  // namespace meshwave
