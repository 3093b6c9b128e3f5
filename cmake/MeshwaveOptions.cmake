# Build options shared by every target. Targets link meshwave_options to get
# the warning flags and the sanitizer flags.
option(MESHWAVE_TESTS "Build the unit and end-to-end tests" ON)
option(MESHWAVE_BENCH "Build the Google Benchmark programs in bench/" OFF)
option(MESHWAVE_WERROR "Treat compiler warnings as errors" OFF)
option(MESHWAVE_WASM
  "Build the browser viewer's WebAssembly decoder when emscripten and node are installed" ON)
option(MESHWAVE_DECODER_ONLY
  "Build only the decoder library (and with emscripten its WebAssembly module, web/decoder)" OFF)
set(MESHWAVE_SANITIZE "" CACHE STRING
    "Semicolon list of sanitizers, e.g. address;undefined or thread")
option(MESHWAVE_FUZZ
  "Build the libFuzzer targets of tests/fuzz (clang only; adds address;undefined sanitizers)" OFF)
if(MESHWAVE_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "MESHWAVE_FUZZ needs clang: -DCMAKE_CXX_COMPILER=clang++")
  endif()
  if(NOT MESHWAVE_SANITIZE)
    set(MESHWAVE_SANITIZE "address;undefined" CACHE STRING
        "Semicolon list of sanitizers, e.g. address;undefined or thread" FORCE)
  endif()
endif()
# Where the shared development meshes live. They are not part of the
# repository: without them the tests that need them skip with one line
# saying so (tests/test_data.h), unless MESHWAVE_REQUIRE_SHARED_MESHES is ON
# (the test command sets it where ../shared is beside the clone or CI is
# set: tools/build_flags.sh), which fails them instead.
set(MESHWAVE_SHARED_MESHES "${PROJECT_SOURCE_DIR}/../shared/data/meshes" CACHE PATH
    "Directory of the shared development meshes")
option(MESHWAVE_REQUIRE_SHARED_MESHES
  "Fail, rather than skip, the tests that need the shared development meshes when they are missing"
  OFF)

add_library(meshwave_options INTERFACE)
target_compile_options(meshwave_options INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wold-style-cast
  -Wcast-align -Woverloaded-virtual -Wnull-dereference -Wimplicit-fallthrough)
if(MESHWAVE_WERROR)
  target_compile_options(meshwave_options INTERFACE -Werror)
endif()
# __FILE__ relative to the repository (GoogleTest's messages name files by
# it): objects then do not depend on where the clone is, also in unity
# builds, whose batch files include sources by absolute path, and the
# compiler cache shares them between clones (tools/compiler_cache.sh).
target_compile_options(meshwave_options INTERFACE
  -fmacro-prefix-map=${PROJECT_SOURCE_DIR}/=)
if(MESHWAVE_SANITIZE)
  list(JOIN MESHWAVE_SANITIZE "," _mw_sanitizers)
  target_compile_options(meshwave_options INTERFACE
    -fsanitize=${_mw_sanitizers} -fno-omit-frame-pointer -fno-sanitize-recover=all)
  target_link_options(meshwave_options INTERFACE -fsanitize=${_mw_sanitizers})
  if(CMAKE_CXX_COMPILER_ID STREQUAL "Clang" AND "undefined" IN_LIST MESHWAVE_SANITIZE)
    # Clang 14's -fsanitize=function (part of undefined) cannot compile the
    # Asio coroutines of the client, the server and their tests: "Cannot
    # represent a difference across sections" (llvm/llvm-project#49689).
    # The codec libraries have no coroutines and keep the check (calls
    # through a function pointer of the wrong type).
    target_compile_options(meshwave_options INTERFACE
      $<$<NOT:$<IN_LIST:$<TARGET_PROPERTY:NAME>,meshwave_codec;meshwave_decoder>>:-fno-sanitize=function>)
  endif()
endif()
if(MESHWAVE_FUZZ)
  # Coverage for libFuzzer in every library; only the fuzz targets link the
  # fuzzer's main (-fsanitize=fuzzer, tests/fuzz/CMakeLists.txt).
  target_compile_options(meshwave_options INTERFACE -fsanitize=fuzzer-no-link)
endif()
