#!/bin/sh
# Builds the WebAssembly decoder with Debian's emscripten (3.1.6):
#   web/build_decoder.sh [BUILD_DIR]        (default: build-wasm)
#   web/build_decoder.sh --dist [BUILD_DIR] and copies it to web/dist/, the
#                                           module shipped for builds without
#                                           emscripten (wasm_dist_test)
# The module is BUILD_DIR/web/decoder/meshwave_decoder.js (an ES module:
# import createMeshwave from './meshwave_decoder.js') with
# meshwave_decoder.wasm beside it, which it fetches.
set -eu
if [ "${1:-}" = "-h" ] || [ "${1:-}" = "--help" ]; then
  sed -n '2,9p' "$0" | sed 's/^# \{0,1\}//'
  exit 0
fi
dist=
if [ "${1:-}" = "--dist" ]; then
  dist=1
  shift
fi
src=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$src/build-wasm}
command -v emcmake >/dev/null || {
  echo "emcmake not found: apt-get install emscripten (deploy/install-deps.sh)" >&2
  exit 1
}
# Debian's emscripten runs its JS optimizer with Debian's node modules.
export NODE_PATH="${NODE_PATH:-/usr/share/nodejs}"
# Eigen is header-only: its CMake package is used from the host (the
# emscripten toolchain looks for packages in its sysroot only).
emcmake cmake -S "$src" -B "$out" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DMESHWAVE_DECODER_ONLY=ON -DMESHWAVE_TESTS=OFF -DMESHWAVE_WERROR=ON -DMESHWAVE_PCH=OFF \
  -DEigen3_DIR=/usr/share/eigen3/cmake >/dev/null
cmake --build "$out" --parallel "${MESHWAVE_JOBS:-2}" --target meshwave_decoder_js
if [ -n "$dist" ]; then
  mkdir -p "$src/web/dist"
  install -m 644 "$out/web/decoder/meshwave_decoder.js" "$out/web/decoder/meshwave_decoder.wasm" \
    "$src/web/dist/"
  echo "$src/web/dist/meshwave_decoder.js"
else
  echo "$out/web/decoder/meshwave_decoder.js"
fi
