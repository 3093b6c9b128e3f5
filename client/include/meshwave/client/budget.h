// How much of a stream to fetch: a byte count, a rate over a time, or an
// estimated quality; and where in a packet order that budget ends.
#ifndef MESHWAVE_CLIENT_BUDGET_H_
#define MESHWAVE_CLIENT_BUDGET_H_

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "meshwave/status.h"
#include "meshwave/stream_header.h"

namespace meshwave::client {

struct Budget {
  enum class Kind { kAll, kBytes, kPsnr };
  Kind kind = Kind::kAll;
  uint64_t bytes = 0;  // kBytes: container bytes, header included
  double psnr_db = 0;  // kPsnr: estimated PSNR (dB) to reach

  static Budget All() { return {}; }
  static Budget Bytes(uint64_t n) { return {Kind::kBytes, n, 0}; }
  static Budget Psnr(double db) { return {Kind::kPsnr, 0, db}; }
};

// A rate in bits per second: "2Mbit", "500kbit", "1.5Gbps", "64000" (bit/s;
// k, M, G are decimal), or bytes per second: "2MB/s", "256KiB/s". Rejects
// zero, negative, non-finite and unknown units (InvalidArgument).
Result<double> ParseRate(std::string_view text);

// A duration in seconds: "1.5s", "200ms", "2min"; a bare number is seconds.
Result<double> ParseDuration(std::string_view text);

// The bytes a link of `bits_per_second` carries in `seconds` (rounded down).
// InvalidArgument when the product is not positive or exceeds 2^50.
Result<uint64_t> RateBudgetBytes(double bits_per_second, double seconds);

// The end cursor of `budget` in `order` (ids of the header's index, the
// header validated): the longest prefix whose container fits kBytes (0 when
// not even the header fits), the shortest prefix whose estimated PSNR
// reaches kPsnr (the whole order when none does), or the whole order.
size_t TargetCursor(const StreamHeader& header,
                    const std::vector<uint32_t>& order, const Budget& budget);

}  // namespace meshwave::client

#endif  // MESHWAVE_CLIENT_BUDGET_H_
