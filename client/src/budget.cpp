#include "meshwave/client/budget.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <string>

#include "meshwave/container.h"
#include "meshwave/progression.h"

namespace meshwave::client {
namespace {

struct Unit {
  std::string_view name;
  double factor;
};

// Splits "1.5Mbit" into 1.5 and "Mbit"; the number must be a plain
// non-negative decimal.
bool SplitNumber(std::string_view text, double& value, std::string_view& unit) {
  size_t i = 0;
  while (
      i < text.size() &&
      (std::isdigit(static_cast<unsigned char>(text[i])) || text[i] == '.')) {
    ++i;
  }
  if (i == 0) return false;
  const std::string number(text.substr(0, i));
  const char* end = number.data() + number.size();
  auto [ptr, ec] = std::from_chars(number.data(), end, value);
  if (ec != std::errc() || ptr != end || !std::isfinite(value)) return false;
  unit = text.substr(i);
  while (!unit.empty() && unit.front() == ' ') unit.remove_prefix(1);
  return true;
}

Result<double> ParseWithUnits(std::string_view text,
                              std::initializer_list<Unit> units,
                              const char* what) {
  double value = 0;
  std::string_view unit;
  if (!SplitNumber(text, value, unit)) {
    return InvalidArgument(std::string(what) + " \"" + std::string(text) +
                           "\" is not a number");
  }
  for (const Unit& u : units) {
    if (unit == u.name) {
      const double v = value * u.factor;
      if (!(v > 0) || !std::isfinite(v)) {
        return InvalidArgument(std::string(what) + " \"" + std::string(text) +
                               "\" must be positive");
      }
      return v;
    }
  }
  return InvalidArgument(std::string(what) + " \"" + std::string(text) +
                         "\": unknown unit \"" + std::string(unit) + "\"");
}

}  // namespace

Result<double> ParseRate(std::string_view text) {
  return ParseWithUnits(text,
                        {{"", 1},
                         {"bit", 1},
                         {"bps", 1},
                         {"bit/s", 1},
                         {"k", 1e3},
                         {"kbit", 1e3},
                         {"Kbit", 1e3},
                         {"kbps", 1e3},
                         {"kbit/s", 1e3},
                         {"M", 1e6},
                         {"Mbit", 1e6},
                         {"Mbps", 1e6},
                         {"Mbit/s", 1e6},
                         {"G", 1e9},
                         {"Gbit", 1e9},
                         {"Gbps", 1e9},
                         {"Gbit/s", 1e9},
                         {"B/s", 8},
                         {"kB/s", 8e3},
                         {"MB/s", 8e6},
                         {"GB/s", 8e9},
                         {"KiB/s", 8.0 * 1024},
                         {"MiB/s", 8.0 * 1024 * 1024},
                         {"GiB/s", 8.0 * 1024 * 1024 * 1024}},
                        "rate");
}

Result<double> ParseDuration(std::string_view text) {
  return ParseWithUnits(text, {{"", 1}, {"s", 1}, {"ms", 1e-3}, {"min", 60}},
                        "duration");
}

Result<uint64_t> RateBudgetBytes(double bits_per_second, double seconds) {
  const double bytes = std::floor(bits_per_second * seconds / 8);
  if (!(bytes >= 1) || bytes > std::ldexp(1.0, 50)) {
    return InvalidArgument("rate × deadline gives " + std::to_string(bytes) +
                           " bytes (expected 1 .. 2^50)");
  }
  return static_cast<uint64_t>(bytes);
}

size_t TargetCursor(const StreamHeader& header,
                    const std::vector<uint32_t>& order, const Budget& budget) {
  switch (budget.kind) {
    case Budget::Kind::kAll:
      return order.size();
    case Budget::Kind::kBytes:
      return SelectPackets(header, order, budget.bytes, 0).next_cursor;
    case Budget::Kind::kPsnr: {
      const std::vector<double> curve = EstimatedPsnrCurve(header, order);
      for (size_t i = 0; i < curve.size(); ++i) {
        if (curve[i] >= budget.psnr_db) return i;
      }
      return order.size();
    }
  }
  return order.size();
}

}  // namespace meshwave::client
