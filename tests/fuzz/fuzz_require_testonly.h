// fuzz::Require, the fuzz targets' invariant check, in a header of its own
// so that targets without the container fixture (the asset readers) use it
// without linking protobuf.
#ifndef MESHWAVE_TESTS_FUZZ_FUZZ_REQUIRE_TESTONLY_H_
#define MESHWAVE_TESTS_FUZZ_FUZZ_REQUIRE_TESTONLY_H_

#include <cstdio>
#include <cstdlib>

namespace meshwave::fuzz {

// A check whose failure is a bug in the code under test: abort, so that
// libFuzzer (and the replay driver) report the input.
inline void Require(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "fuzz invariant violated: %s\n", what);
    std::abort();
  }
}

}  // namespace meshwave::fuzz

#endif  // MESHWAVE_TESTS_FUZZ_FUZZ_REQUIRE_TESTONLY_H_
