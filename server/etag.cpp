#include "etag.h"

namespace meshwave::server {

namespace {

std::string_view Trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

}  // namespace

std::string StrongEtag(std::string_view sha256, std::string_view variant) {
  std::string tag = "\"";
  tag += sha256;
  if (!variant.empty()) {
    tag += '-';
    tag += variant;
  }
  tag += '"';
  return tag;
}

bool IfNoneMatchMatches(std::string_view header, std::string_view etag) {
  header = Trim(header);
  if (header == "*") return true;
  while (!header.empty()) {
    const size_t comma = header.find(',');
    std::string_view tag = Trim(header.substr(0, comma));
    header = comma == std::string_view::npos ? "" : header.substr(comma + 1);
    if (tag.starts_with("W/")) tag.remove_prefix(2);
    if (tag == etag) return true;
  }
  return false;
}

bool IfRangeHolds(std::string_view header, std::string_view etag) {
  // A strong comparison: both tags strong and equal character by character.
  return Trim(header) == etag && !etag.starts_with("W/");
}

}  // namespace meshwave::server
