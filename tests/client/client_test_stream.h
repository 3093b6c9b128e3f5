// A small encoded stream shared by the client's unit tests.
#ifndef MESHWAVE_TESTS_CLIENT_CLIENT_TEST_STREAM_H_
#define MESHWAVE_TESTS_CLIENT_CLIENT_TEST_STREAM_H_

#include <gtest/gtest.h>

#include <cstdint>
#include <string_view>

#include "codec/stream/stream_test_util.h"
#include "meshwave/container.h"
#include "meshwave/encoder.h"

namespace meshwave::testing {

inline const EncodedStream& ClientTestStream() {
  static const EncodedStream s = [] {
    auto r = EncodeMesh(BumpySphere(3), EncodeOptions{});
    EXPECT_TRUE(r.ok());
    return *std::move(r);
  }();
  return s;
}

// The header length field of a container (bytes 4-7, little endian): what
// the client's max_header_bytes is compared with.
inline uint64_t HeaderLengthField(std::string_view container) {
  const Result<uint32_t> length = ReadContainerHeaderLength(container);
  EXPECT_TRUE(length.ok()) << length.status().ToString();
  return length.ok() ? *length : 0;
}

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_CLIENT_CLIENT_TEST_STREAM_H_
