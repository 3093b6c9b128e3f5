#!/usr/bin/env bash
# The figures of docs/ANALYSIS.md for one mesh (default: the remeshed Stanford
# bunny, as in Satti et al. 2011, Fig. 11):
#   - `meshwave analyze --plots docs/analysis/<mesh>` with a Draco RD curve
#     (draco_encoder -cl 10 -qp 6..12 on the semi-regular mesh, PSNR from
#     `meshwave compare --match nearest`, rate = whole .drc file);
#   - a strip rendered at five budgets (0.05 ... 2 bpv, base excluded):
#     `meshwave encode`, `decode --budget`, `render --reference` the full
#     decode (same vertex order; precision 16 is above 90 dB, so it stands
#     for the original), green to red at 0.1 % of the diagonal.
# Prints the Markdown strip table on stdout.
#
# Usage: bench/analysis_figures.sh [BUILD_DIR] [MESH]   (needs jq, gnuplot; draco optional)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
name=${2:-bunny_stanford_zipper.ply}
cli=$build/tools/meshwave/meshwave
meshes=${MESHWAVE_SHARED_MESHES:-$root/../shared/data/meshes}
cache=${CACHE:-/tmp/meshwave-analysis-cache}
view=${VIEW:-0,0}
stem=${name%.*}
figs=$root/docs/analysis/$stem
mkdir -p "$cache" "$figs"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

src=$meshes/$name
if "$cli" info "$src" --json 2> /dev/null | jq -e '.semiregular_levels > 0' > /dev/null; then
  sr=$src
else
  sr=$cache/$stem.sr.ply
  [[ -f $sr ]] || "$cli" remesh "$src" "$sr" > /dev/null
fi
v=$("$cli" info "$sr" --json | jq -r '.file_vertices')

# Draco at several quantisation levels.
draco=()
if [[ -z ${SKIP_ANALYZE:-} ]] && command -v draco_encoder > /dev/null; then
  echo "bpv,psnr_db" > "$figs/draco.csv"
  for qp in 6 7 8 9 10 11 12; do
    draco_encoder -i "$sr" -o "$tmp/d.drc" -cl 10 -qp $qp > /dev/null
    draco_decoder -i "$tmp/d.drc" -o "$tmp/d.ply" > /dev/null
    psnr=$("$cli" compare "$sr" "$tmp/d.ply" --match nearest --json 2> /dev/null | jq -r '.vertex_error.rms.psnr_db')
    bytes=$(stat -c %s "$tmp/d.drc")
    echo "$(echo "8 * $bytes / $v" | bc -l),$psnr" >> "$figs/draco.csv"
  done
  draco=(--draco-csv "$figs/draco.csv")
fi
[[ -n ${SKIP_ANALYZE:-} ]] || nice "$cli" analyze "$sr" --plots "$figs" "${draco[@]}" > "$figs/analyze.txt" 2> /dev/null

# The strip.
"$cli" encode "$sr" "$tmp/s.mwv" > "$tmp/enc.txt" 2> /dev/null
"$cli" decode "$tmp/s.mwv" "$tmp/full.ply" > /dev/null 2>&1
total=$(stat -c %s "$tmp/s.mwv")
header=$(sed -n 's/.*(header \([0-9]*\) incl.*/\1/p' "$tmp/enc.txt")
row1="|" row2="|" sep="|"
# Packets are large at low rates: targets spread wide enough to give five
# different prefixes.
for bpv in ${BUDGETS:-0.05 0.2 0.5 1 2}; do
  budget=$(echo "$header + $bpv * $v / 8" | bc -l | cut -d. -f1)
  "$cli" decode "$tmp/s.mwv" "$tmp/p.ply" --budget "$budget" --json > "$tmp/dec.json" 2> /dev/null
  bytes=$(jq -r '.bytes // .container_bytes // empty' "$tmp/dec.json" 2> /dev/null || true)
  [[ -n $bytes ]] || bytes=$budget
  psnr=$("$cli" compare "$tmp/full.ply" "$tmp/p.ply" --json 2> /dev/null | jq -r '.vertex_error.rms.psnr_db')
  png=strip_${bpv}.png
  "$cli" render "$tmp/p.ply" "$figs/$png" --reference "$tmp/full.ply" --view "$view" \
    --width 360 --height 360 2> /dev/null
  real=$(echo "8 * ($bytes - $header) / $v" | bc -l)
  row1+=" ![${bpv} bpv](analysis/$stem/$png) |"
  row2+=" $(printf '%.3f bpv, %.1f dB' "$real" "$psnr") |"
  sep+="---|"
done
echo "$row1"
echo "$sep"
echo "$row2"
