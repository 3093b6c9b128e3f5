// A small encoded stream shared by the client's unit tests.
#ifndef MESHWAVE_TESTS_CLIENT_CLIENT_TEST_STREAM_H_
#define MESHWAVE_TESTS_CLIENT_CLIENT_TEST_STREAM_H_

#include <gtest/gtest.h>

#include "codec/stream/stream_test_util.h"
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

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_CLIENT_CLIENT_TEST_STREAM_H_
