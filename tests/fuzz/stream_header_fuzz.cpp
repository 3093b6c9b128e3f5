// Differential fuzz target: the decoder's hand-written header reader
// (ReadStreamHeader) against protobuf's parser on the same bytes. Both must
// accept or both refuse; when both accept, every field must be equal (bit
// for bit), and re-reading protobuf's re-serialization must give the same
// fields and, as bytes_without_present, protobuf's bytes without `present`.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

#include "../codec/stream/stream_header_compare_testonly.h"
#include "fuzz_fixture_testonly.h"  // fuzz::Require, protobuf's logging off
#include "meshwave/stream_header.h"

using namespace meshwave;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  proto::StreamHeader p;
  const bool proto_ok = p.ParseFromArray(data, static_cast<int>(size));
  auto r = ReadStreamHeader(bytes);
  if (r.ok() != proto_ok) {
    std::fprintf(stderr, "protobuf %s, ReadStreamHeader %s\n", proto_ok ? "parses" : "refuses",
                 r.ok() ? "reads" : "refuses");
  }
  fuzz::Require(r.ok() == proto_ok, "both readers accept the same bytes");
  if (!proto_ok) return 0;
  const std::string diff = testing::HeaderDifference(*r, p);
  if (!diff.empty()) std::fprintf(stderr, "field %s differs\n", diff.c_str());
  fuzz::Require(diff.empty(), "both readers read the same fields");
  auto again = ReadStreamHeader(p.SerializeAsString());
  fuzz::Require(again.ok(), "protobuf's serialization reads");
  fuzz::Require(testing::HeaderDifference(*again, p).empty(), "and reads the same fields");
  fuzz::Require(again->bytes_without_present == testing::ProtoBytesWithoutPresent(p),
                "bytes_without_present are protobuf's bytes without present");
  return 0;
}
