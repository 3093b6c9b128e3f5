#!/usr/bin/env bash
# What the original layer (docs/FORMAT.md 2.5) costs on each mesh, beside
# Draco's whole file at qp 14 for scale: `meshwave encode` at default
# settings (the layer's figures are its own print-out: connectivity with the
# vertex ids, positions at --precision 16 in all its packets) and the
# remesh's bytes before it; then decode of the complete stream, the layer
# included, against Draco's decode of its qp-14 file (best of 3 each, whole
# processes as a user runs them; the machine's load is printed).
#
# Usage: bench/original_layer_table.sh [BUILD_DIR]     (needs draco, jq)
#   MESHES="a.ply b.obj"   other meshes (default: every shared one)
#   ENCODE_ARGS="..."      more `meshwave encode` options (e.g. "--fidelity 0":
#                          one remesh, much faster; the layer then has no
#                          refinement planes but the same total)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
cli=$build/tools/meshwave/meshwave
[[ -x $cli ]] || { echo "no meshwave binary at $cli (build first)" >&2; exit 1; }
source "$root/bench/lib.sh"
need_tools draco_encoder draco_decoder jq
shared=$root/../shared/data/meshes
if [[ -z ${MESHES:-} ]]; then
  [[ -d $shared ]] || { echo "no shared meshes at $shared: set MESHES" >&2; exit 1; }
  MESHES=$(ls "$shared"/*.ply "$shared"/*.obj)
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

best_of_3() {  # best_of_3 CMD...: the fastest wall time in ms
  local best=
  for _ in 1 2 3; do
    local t0 t1 ms
    t0=$(date +%s%N); "$@" > /dev/null 2>&1; t1=$(date +%s%N)
    ms=$(( (t1 - t0) / 1000000 ))
    [[ -z $best || $ms -lt $best ]] && best=$ms
  done
  echo "$best"
}

echo "load: $(cut -d' ' -f1-3 /proc/loadavg)"
printf '| mesh | V | remesh bytes | connectivity bytes (bits/V) | positions bytes (bits/V), packets | complete stream | Draco qp 14 | ratio | decode ms: meshwave complete / Draco qp 14 |\n'
printf '|---|---|---|---|---|---|---|---|---|\n'
for mesh in $MESHES; do
  name=$(basename "${mesh%.*}")
  # shellcheck disable=SC2086
  "$cli" encode "$mesh" "$tmp/$name.mwv" ${ENCODE_ARGS:-} > "$tmp/$name.txt" 2> /dev/null
  line=$(grep '^original layer:' "$tmp/$name.txt" || true)
  [[ -n $line ]] || { echo "| $name | (no original layer) |"; continue; }
  v=$(sed -E 's/^original layer: ([0-9]+) vertices.*/\1/' <<< "$line")
  conn=$(sed -E 's/.*connectivity ([0-9]+) bytes \(([0-9.]+) bits.*/\1 (\2)/' <<< "$line")
  pos=$(sed -E 's/.*positions ([0-9]+) bytes \(([0-9.]+) bits per vertex\) in ([0-9]+) \+ 1 packets.*/\1 (\2), \3 + 1/' <<< "$line")
  total=$(stat -c %s "$tmp/$name.mwv")
  layer=$(( ${conn%% *} + ${pos%% *} ))
  draco_encoder -i "$mesh" -o "$tmp/$name.drc" -cl 10 -qp 14 > /dev/null
  draco=$(stat -c %s "$tmp/$name.drc")
  ms=$(best_of_3 "$cli" decode "$tmp/$name.mwv" "$tmp/$name.ply")
  dms=$(best_of_3 draco_decoder -i "$tmp/$name.drc" -o "$tmp/$name.draco.ply")
  printf '| %s | %s | %s | %s | %s | %s | %s | %.2fx | %s / %s |\n' "$name" "$v" \
    "$(( total - layer ))" "$conn" "$pos" "$total" "$draco" \
    "$(bc -l <<< "$total / $draco")" "$ms" "$dms"
done
echo "load: $(cut -d' ' -f1-3 /proc/loadavg)"
