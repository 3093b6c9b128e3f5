#!/usr/bin/env bash
# Time to the first drawn mesh in the browser viewer (headless Chromium,
# loopback), from navigation to /viewer/?mesh=ID, warm and cold:
# bench/viewer_first_mesh.mjs, with the npm packages of web/package-lock.json.
# A textured mesh (MESH=data/textured/die.obj) also gets the time to the
# first frame drawn with a texture level applied, from the same runs.
#
# Usage: bench/viewer_first_mesh.sh [BUILD_DIR]     (default: build)
#   Needs BUILD_DIR/server/meshwave-server, BUILD_DIR/tools/meshwave/meshwave
#   and the WebAssembly decoder module (DECODER_JS, default
#   BUILD_DIR/viewer/meshwave_decoder.js, with its .wasm beside it);
#   /usr/bin/chromium. Builds nothing.
# Environment:
#   MESH=FILE     default data/elephant.off (remeshed at ingest)
#   RUNS=9        runs per budget and cache state (medians reported)
#   BUDGETS="6 all"  budgets in KiB, "all" for the whole stream
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
[[ $build = /* ]] || build=$PWD/$build
decoder=${DECODER_JS:-$build/viewer/meshwave_decoder.js}
[[ -x $build/server/meshwave-server && -x $build/tools/meshwave/meshwave ]] ||
  { echo "build meshwave-server and meshwave first" >&2; exit 1; }
[[ -f $decoder ]] || { echo "no decoder module at $decoder (set DECODER_JS)" >&2; exit 1; }
[[ -x /usr/bin/chromium ]] || { echo "/usr/bin/chromium missing (deploy/install-deps.sh)" >&2; exit 1; }
modules=$(bash "$root/web/npm_ci.sh" "$build/bench/npm")
# shellcheck disable=SC2086
exec node "$root/bench/viewer_first_mesh.mjs" "$build/server/meshwave-server" \
  "$build/tools/meshwave/meshwave" "$decoder" "${MESH:-$root/data/elephant.off}" "$modules" \
  "${RUNS:-9}" ${BUDGETS:-6 all}
