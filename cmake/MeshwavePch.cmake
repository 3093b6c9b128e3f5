# Precompiled headers. Much of a file's compile time is spent parsing the
# same headers: a codec file preprocesses to ~110,000 lines, a third of
# them Eigen; a server or client file to ~220,000 with Asio and Beast; a
# test adds GoogleTest. Each library, the CLI and every test binary of two
# or more files parses them once.
# On by default for clang only (the ASan + UBSan stage), where it pays:
# server library 319 -> 227 s. GCC 12 writes 110-340 MB per header and
# reads all of it for every file: its system time doubles and the client,
# server, CLI and tests built slower with it, only the codec faster
# (docs/BENCHMARKS.md, "Build time"; bench/build_time.sh).
if(CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  set(_mw_pch_default ON)
else()
  set(_mw_pch_default OFF)
endif()
option(MESHWAVE_PCH "Precompile the headers every file includes" ${_mw_pch_default})

set(MESHWAVE_PCH_CODEC
  <algorithm> <array> <cmath> <cstdint> <cstring> <functional> <memory>
  <optional> <span> <string> <string_view> <unordered_map> <utility> <vector>
  <Eigen/Core> <Eigen/Geometry>)
set(MESHWAVE_PCH_TEST ${MESHWAVE_PCH_CODEC} <gtest/gtest.h> <gmock/gmock.h>)

# meshwave_precompile(<target> <headers...>): <target>'s own precompiled
# header. One per target rather than shared (REUSE_FROM): targets differ in
# definitions and sanitizer flags, and clang refuses a header precompiled
# with other macros.
function(meshwave_precompile target)
  if(MESHWAVE_PCH)
    target_precompile_headers(${target} PRIVATE ${ARGN})
  endif()
endfunction()
