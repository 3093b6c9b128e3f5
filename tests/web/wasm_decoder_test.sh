#!/bin/sh
# The WebAssembly decoder gives the native decoder's meshes bit for bit:
#   wasm_decoder_test.sh MESHWAVE_CLI WASM_REFERENCE MODULE.js SAMPLE_DIR SHARED_DIR
# encodes every sample mesh (SAMPLE_DIR/*.off, *.ply and the coloured and
# textured textured/*.ply, *.obj: the repository's data/) and every shared development
# mesh (SHARED_DIR; skipped with one line when absent) with the native `meshwave encode`, and the samples
# again with small precincts (many split packets: docs/FORMAT.md 2.2), takes
# the fuzz fixtures' containers (tests/fuzz/data/*.mwv, split too), has
# wasm_reference write the native decoder's output at five budgets in the
# three orders and, for split packets, unit by unit, and runs
# wasm_decoder_test.mjs on it under Node.
set -eu
if [ "${1:-}" = "-h" ] || [ "${1:-}" = "--help" ]; then
  sed -n '2,8p' "$0" | sed 's/^# \{0,1\}//'
  exit 0
fi
[ $# -eq 5 ] || { echo "usage: $0 MESHWAVE_CLI WASM_REFERENCE MODULE.js SAMPLE_DIR SHARED_DIR" >&2; exit 2; }
cli=$1 reference=$2 module=$3 samples=$4 shared=$5
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

dirs=""
reference() {  # reference CONTAINER NAME: write the native reference
  mkdir "$work/$2"
  "$reference" "$1" "$work/$2"
  dirs="$dirs $work/$2"
}
add() {  # add MESH [SUFFIX ENCODE_OPTIONS...]: encode it, write the native reference
  mesh=$1
  name=$(basename "$mesh")
  name=${name%.*}${2:-}
  shift $(($# < 2 ? $# : 2))
  "$cli" encode "$mesh" "$work/$name.mwv" "$@" >/dev/null 2>"$work/$name.log" || {
    cat "$work/$name.log" >&2
    echo "meshwave encode $mesh failed" >&2
    exit 1
  }
  reference "$work/$name.mwv" "$name"
}
for mesh in "$samples"/*.off "$samples"/*.ply; do
  if [ -e "$mesh" ]; then
    add "$mesh"
    add "$mesh" _precincts --precinct-size 256 --split-bytes 8
  fi
done
# The coloured and textured samples: colours, UVs and texture levels are
# compared too.
for mesh in "$samples"/textured/*.ply "$samples"/textured/*.obj; do
  if [ -e "$mesh" ]; then add "$mesh"; fi
done
for container in "$here"/../fuzz/data/*.mwv; do
  name=$(basename "$container" .mwv)
  reference "$container" "fixture_$name"
done
if [ -d "$shared" ]; then
  for mesh in "$shared"/*.off "$shared"/*.ply "$shared"/*.obj; do
    if [ -e "$mesh" ]; then add "$mesh"; fi
  done
else
  echo "shared meshes not found at $shared: compared the sample meshes only"
fi
# shellcheck disable=SC2086  # $dirs: one word per directory (mktemp paths)
exec node "$here/wasm_decoder_test.mjs" "$module" $dirs
