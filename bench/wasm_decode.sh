#!/usr/bin/env bash
# The WebAssembly decoder against the native one (issue 18): decode speed
# on the same streams (bench/decode_rate vs bench/wasm_decode_rate.mjs under
# Node: CPU per payload byte through AddPacket, and the mesh reconstruction),
# and the module's download size beside Draco's decoder.
#
# Usage: bench/wasm_decode.sh BUILD_DIR BENCH_BUILD_DIR MODULE.js [MESH...]
#   BUILD_DIR        a build with tools/meshwave/meshwave (to encode)
#   BENCH_BUILD_DIR  a -DMESHWAVE_BENCH=ON build with bench/decode_rate
#   MODULE.js        web/build_decoder.sh's output
#   MESH...          meshes to encode, or .mwv streams (default:
#                    data/elephant.off and the shared bunny and horse)
# DRACO3D_DIR (a directory holding npm draco3d's draco_decoder.wasm and
# draco_decoder_nodejs.js) adds Draco's decoder sizes. RUNS sets the runs
# per measurement (default 9). Run it niced on a quiet machine.
set -euo pipefail
usage() { sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//'; }
if [[ ${1:-} = -h || ${1:-} = --help ]]; then usage; exit 0; fi
if [[ $# -lt 3 ]]; then usage >&2; exit 2; fi
root=$(cd "$(dirname "$0")/.." && pwd)
cli=$1/tools/meshwave/meshwave
rate=$2/bench/decode_rate
module=$3
shift 3
meshes=("$@")
shared=${MESHWAVE_SHARED_MESHES:-$root/../shared/data/meshes}
if [[ ${#meshes[@]} -eq 0 ]]; then
  meshes=("$root/data/elephant.off" "$shared/bunny_stanford_zipper.ply" "$shared/horse_cyberware.ply")
fi
runs=${RUNS:-9}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

median_of() { sed -n 's/^median: \([0-9.]*\) ns CPU.*/\1/p'; }
mesh_ms_native() { sed -n 's/^median:.*Mesh() \([0-9.]*\) ms CPU.*/\1/p'; }
mesh_ms_wasm() { sed -n 's/^median:.*positions()+faces() \([0-9.]*\) ms wall.*/\1/p'; }

echo "| mesh | vertices | payload bytes | native ns/byte | WASM ns/byte | WASM speed / native | native Mesh() ms | WASM positions()+faces() ms |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- |"
for mesh in "${meshes[@]}"; do
  [[ -e $mesh ]] || { echo "skipped (absent): $mesh" >&2; continue; }
  name=$(basename "${mesh%.*}")
  if [[ $mesh = *.mwv ]]; then
    cp "$mesh" "$tmp/$name.mwv"
  else
    "$cli" encode "$mesh" "$tmp/$name.mwv" > /dev/null
  fi
  "$rate" "$tmp/$name.mwv" --runs "$runs" > "$tmp/$name.native"
  # One thread (V8 compiles and collects garbage on others, which process
  # CPU time would count) and TurboFan from the start (the code a page runs
  # once V8 has tiered up): the CPU figure is the decode's alone.
  node --single-threaded --no-liftoff "$root/bench/wasm_decode_rate.mjs" "$module" "$tmp/$name.mwv" \
    --runs "$runs" > "$tmp/$name.wasm"
  native=$(median_of < "$tmp/$name.native")
  wasm=$(median_of < "$tmp/$name.wasm")
  vertices=$(sed -n 's/.*(\([0-9]*\) vertices).*/\1/p' "$tmp/$name.native" | head -1)
  payload=$(sed -n 's/.*packets, \([0-9]*\) payload bytes.*/\1/p' "$tmp/$name.native" | head -1)
  ratio=$(awk -v n="$native" -v w="$wasm" 'BEGIN { printf "%.2f", n / w }')
  echo "| $name | $vertices | $payload | $native | $wasm | ${ratio}x | $(mesh_ms_native < "$tmp/$name.native") | $(mesh_ms_wasm < "$tmp/$name.wasm") |"
done

# Sizes: what a page downloads, raw and gzip -9: the module's JS (API and
# embind glue) and its wasm.
gz() { gzip -9 -c "$1" | wc -c; }
wasm_file=${module%.js}.wasm
echo
echo "| file | bytes | gzip -9 bytes |"
echo "| --- | --- | --- |"
echo "| meshwave_decoder.js | $(wc -c < "$module") | $(gz "$module") |"
echo "| meshwave_decoder.wasm | $(wc -c < "$wasm_file") | $(gz "$wasm_file") |"
echo "| both | $(( $(wc -c < "$module") + $(wc -c < "$wasm_file") )) | $(( $(gz "$module") + $(gz "$wasm_file") )) |"
if [[ -n ${DRACO3D_DIR:-} ]]; then
  for f in draco_decoder.wasm draco_decoder_nodejs.js; do
    echo "| draco3d $f | $(wc -c < "$DRACO3D_DIR/$f") | $(gz "$DRACO3D_DIR/$f") |"
  done
fi
