#include "byte_range.h"

#include <algorithm>

#include "request_target.h"

namespace meshwave::server {

RangeRequest ParseRange(std::string_view header, uint64_t size) {
  RangeRequest r;
  constexpr std::string_view kUnit = "bytes=";
  if (!header.starts_with(kUnit)) return r;
  std::string_view spec = header.substr(kUnit.size());
  if (spec.find(',') != std::string_view::npos) return r;  // several ranges
  while (!spec.empty() && spec.back() == ' ') spec.remove_suffix(1);
  const size_t dash = spec.find('-');
  RangeRequest bad;
  bad.kind = RangeRequest::kUnsatisfiable;
  if (dash == std::string_view::npos) return bad;
  const std::string_view a = spec.substr(0, dash), b = spec.substr(dash + 1);
  constexpr uint64_t kMax = ~uint64_t{0} >> 1;
  if (a.empty()) {  // suffix: the last n bytes
    auto n = ParseUnsigned(b, kMax, "range");
    if (!n.ok() || *n == 0 || size == 0) return bad;
    r.kind = RangeRequest::kPartial;
    r.first = size - std::min(*n, size);
    r.last = size - 1;
    return r;
  }
  auto first = ParseUnsigned(a, kMax, "range");
  if (!first.ok() || *first >= size) return bad;
  uint64_t last = size - 1;
  if (!b.empty()) {
    auto l = ParseUnsigned(b, kMax, "range");
    if (!l.ok() || *l < *first) return bad;
    last = std::min(*l, size - 1);
  }
  r.kind = RangeRequest::kPartial;
  r.first = *first;
  r.last = last;
  return r;
}

}  // namespace meshwave::server
