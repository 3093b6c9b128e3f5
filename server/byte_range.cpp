#include "byte_range.h"

#include <algorithm>
#include <optional>
#include <vector>

namespace meshwave::server {
namespace {

constexpr uint64_t kSaturated = ~uint64_t{0};

bool IsOws(char c) { return c == ' ' || c == '\t'; }

std::string_view TrimOws(std::string_view s) {
  while (!s.empty() && IsOws(s.front())) s.remove_prefix(1);
  while (!s.empty() && IsOws(s.back())) s.remove_suffix(1);
  return s;
}

bool IsDigits(std::string_view s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// 1*DIGIT as a number, saturating instead of overflowing.
uint64_t ToNumber(std::string_view digits) {
  uint64_t v = 0;
  for (char c : digits) {
    const uint64_t d = static_cast<uint64_t>(c - '0');
    if (v > (kSaturated - d) / 10) return kSaturated;
    v = v * 10 + d;
  }
  return v;
}

// The client's text quoted in a message: bounded and printable.
std::string Shown(std::string_view s) {
  std::string out(s.substr(0, 40));
  for (char& c : out) {
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) > 0x7e) c = '?';
  }
  if (s.size() > 40) out += "...";
  return "'" + out + "'";
}

struct Span {
  uint64_t first, last;  // inclusive
};

RangeRequest Refuse(std::string problem) {
  RangeRequest r;
  r.kind = RangeRequest::kUnsatisfiable;
  r.problem = std::move(problem);
  return r;
}

}  // namespace

RangeRequest ParseRange(std::string_view header, uint64_t size) {
  const size_t eq = header.find('=');
  if (eq == std::string_view::npos) {
    return Refuse("Range " + Shown(header) + " is not unit=ranges (RFC 9110 14.1.1)");
  }
  constexpr std::string_view kBytes = "bytes";
  const std::string_view unit = header.substr(0, eq);
  const bool bytes = unit.size() == kBytes.size() &&
                     std::equal(unit.begin(), unit.end(), kBytes.begin(), [](char a, char b) {
                       return (a >= 'A' && a <= 'Z' ? a - 'A' + 'a' : a) == b;
                     });
  if (!bytes) return {};  // a unit we do not serve: ignored
  std::string_view set = header.substr(eq + 1);
  std::vector<Span> spans;
  int elements = 0;
  bool any = false;
  while (true) {
    const size_t comma = set.find(',');
    const std::string_view spec = TrimOws(set.substr(0, comma));
    if (!spec.empty()) {
      any = true;
      if (++elements > kMaxRanges) return {};
      const size_t dash = spec.find('-');
      const std::string_view a = spec.substr(0, dash);
      const std::string_view b = dash == std::string_view::npos ? "" : spec.substr(dash + 1);
      if (dash == std::string_view::npos || (!a.empty() && !IsDigits(a)) ||
          (!b.empty() && !IsDigits(b)) || (a.empty() && b.empty())) {
        return Refuse("range " + Shown(spec) +
                      " is not first-last, first- or -suffix in decimal digits");
      }
      if (a.empty()) {  // suffix-range: the last n bytes
        const uint64_t n = ToNumber(b);
        if (n > 0 && size > 0) spans.push_back({size - std::min(n, size), size - 1});
      } else {
        const uint64_t first = ToNumber(a);
        const uint64_t last = b.empty() ? kSaturated : ToNumber(b);
        if (last < first) {
          return Refuse("range " + Shown(spec) + " ends before it starts");
        }
        if (first < size) spans.push_back({first, std::min(last, size - 1)});
      }
    }
    if (comma == std::string_view::npos) break;
    set.remove_prefix(comma + 1);
  }
  if (!any) return Refuse("Range " + Shown(header) + " lists no range");
  if (spans.empty()) {
    return Refuse("no range of " + Shown(header) + " starts inside the " +
                  std::to_string(size) + " bytes (positions 0 to " +
                  (size == 0 ? std::string("none") : std::to_string(size - 1)) + ")");
  }
  std::sort(spans.begin(), spans.end(), [](const Span& x, const Span& y) { return x.first < y.first; });
  Span merged = spans.front();
  for (const Span& s : spans) {
    // Overlapping or adjacent (last + 1 == first) ranges make one.
    if (s.first > merged.last && s.first - merged.last > 1) return {};  // disjoint: the whole
    merged.last = std::max(merged.last, s.last);
  }
  RangeRequest r;
  r.kind = RangeRequest::kPartial;
  r.first = merged.first;
  r.last = merged.last;
  return r;
}

}  // namespace meshwave::server
