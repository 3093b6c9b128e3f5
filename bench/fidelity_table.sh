#!/usr/bin/env bash
# What `--fidelity` buys (issue 17, item 1): for every shared mesh of at
# least 5,000 vertices, `meshwave encode` at the default density and with
# --fidelity DB for each DB of $FIDELITIES: the complete stream's symmetric
# surface PSNR against the ORIGINAL mesh (as encode --fidelity measures it:
# `meshwave compare`'s figure, peak = the original's bounding-box diagonal),
# the finest level's vertices and their ratio to the input's, the stream's
# bytes and the encode's wall time. The default row is `--fidelity 1`,
# which any remesh reaches at once: the default remesh and precision,
# measured. With Draco installed (apt-get install draco), each mesh gets a
# row for Draco's default, `draco_encoder -cl 10 -qp 11` on the original,
# measured the same way: what "the default reaches Draco's default" means.
#
# Usage: bench/fidelity_table.sh [BUILD_DIR]
#   FIDELITIES="84 90"      the fidelities to ask for (dB)
#   MAX_VERTEX_RATIO=16      encode's --max-vertex-ratio
#   MESHES="a.ply b.obj"     other meshes (default: the shared ones >= 5 k vertices)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
cli=$build/tools/meshwave/meshwave
[[ -x $cli ]] || { echo "no meshwave binary at $cli (build first)" >&2; exit 1; }
source "$root/bench/lib.sh"
shared=$root/../shared/data/meshes
[[ -n ${MESHES:-} ]] || MESHES=$(shared_meshes_of_at_least 5000)
fidelities=${FIDELITIES:-84 90}
ratio=${MAX_VERTEX_RATIO:-16}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

echo "| mesh (vertices) | asked | reached (dB) | finest vertices (x input) | bytes | encode s |"
echo "|---|---|---|---|---|---|"
for mesh in $MESHES; do
  name=$(basename "$mesh")
  inputv=$("$cli" info "$mesh" --json 2> /dev/null | jq -r '.as_read.vertices // .vertices')
  start=$(date +%s.%N)
  if command -v draco_encoder > /dev/null &&
    draco_encoder -i "$mesh" -o "$tmp/d.drc" -cl 10 -qp 11 > /dev/null 2>&1; then  # PLY, OBJ only
    secs=$(echo "$(date +%s.%N) - $start" | bc)
    draco_decoder -i "$tmp/d.drc" -o "$tmp/d.ply" > /dev/null
    psnr=$("$cli" compare "$mesh" "$tmp/d.ply" --json | jq '.surface.rms.psnr_db')
    dv=$("$cli" info "$tmp/d.ply" --json 2> /dev/null | jq -r '.as_read.vertices // .vertices')
    printf '| %s (%s) | Draco -qp 11 | %.2f | %s | %s | %.1f |\n' "$name" "$inputv" "$psnr" "$dv" \
      "$(stat -c %s "$tmp/d.drc")" "$secs"
  fi
  for f in 1 $fidelities; do
    echo "$name --fidelity $f" >&2
    start=$(date +%s.%N)
    "$cli" encode "$mesh" "$tmp/s.mwv" --fidelity "$f" --max-vertex-ratio "$ratio" \
      > "$tmp/out" 2> "$tmp/err" || { cat "$tmp/err" >&2; exit 1; }
    secs=$(echo "$(date +%s.%N) - $start" | bc)
    reached=$(sed -n 's/.*the complete stream is at \([0-9.]*\) dB.*/\1/p' "$tmp/out")
    verts=$(sed -n 's/^\([0-9]*\) vertices, .*/\1/p' "$tmp/out")
    asked=$f; [[ $f == 1 ]] && asked="default"
    printf '| %s (%s) | %s | %s | %s (%.2fx) | %s | %.1f |\n' "$name" "$inputv" "$asked" "$reached" \
      "$verts" "$(echo "$verts / $inputv" | bc -l)" "$(stat -c %s "$tmp/s.mwv")" "$secs"
  done
done
