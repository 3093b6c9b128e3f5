#!/usr/bin/env bash
# The test command: installs dependencies, builds everything with warnings as
# errors, runs the whole test suite and clang-tidy on the codec
# (tools/tidy.sh), then the sanitizer stages (ASan + UBSan, TSan:
# tools/sanitize.sh). CI runs exactly this (.ci/run).
#   SANITIZE=0 bash tools/test.sh    the Release stage only (a quick local run)
set -euo pipefail
cd "$(dirname "$0")/.."
bash deploy/install-deps.sh
source tools/compiler_cache.sh
[[ ${CMAKE_CXX_COMPILER_LAUNCHER:-} == ccache ]] && ccache --zero-stats > /dev/null
start=$SECONDS
# Unity builds (tools/build_flags.sh): CI's time goes into compiling.
source tools/build_flags.sh
# MESHWAVE_TESTS and MESHWAVE_WASM explicitly: the main job (tools/demo.sh)
# configures the same build directory without them.
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DMESHWAVE_WERROR=ON \
  -DMESHWAVE_TESTS=ON -DMESHWAVE_WASM=ON "${ci_build_flags[@]}"
cmake --build build -j2
built=$SECONDS
ctest --test-dir build --output-on-failure -j2 --timeout 900
tested=$SECONDS
bash tools/tidy.sh build
echo "test: Release stage passed (build $((built - start)) s, tests $((tested - built)) s," \
  "clang-tidy $((SECONDS - tested)) s)"
if [[ ${SANITIZE:-1} != 0 ]]; then
  bash tools/sanitize.sh all
fi
if [[ ${CMAKE_CXX_COMPILER_LAUNCHER:-} == ccache ]]; then
  echo "test: compiler cache: $(ccache --print-stats | awk -F'\t' '$1 ~ /^(direct_cache_hit|preprocessed_cache_hit|cache_miss)$/ {printf "%s %s ", $1, $2}')"
fi
echo "test: all stages passed ($((SECONDS - start)) s)"
