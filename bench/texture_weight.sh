#!/usr/bin/env bash
# Texture against geometry in the quality order: a textured mesh encoded
# with several --texture-weight values, each decoded at a range of budgets
# and rendered (`meshwave render`, two views), each picture compared with
# the original's by bench/render_psnr.py (dB over the pixels drawn). The
# weight that sends the texture levels where they pay most on screen is the
# encoder's default (EncodeOptions::texture_rd_weight).
#
# Usage: bench/texture_weight.sh [BUILD_DIR] [MESH] [OUT_DIR]
#   defaults: build, ../shared/data/textured/spot/cow.obj, a temporary directory
#   WEIGHTS="1 0.01 0.001 0.0001 0.00001 0.000001"  BUDGETS="10000 20000 30000 50000 60000 90000"
#   VIEWS="30,20 210,10"  SIZE=600
set -euo pipefail
if [[ ${1:-} == -h || ${1:-} == --help ]]; then sed -n '2,14p' "$0" | sed 's/^# \{0,1\}//'; exit 0; fi
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
mesh=${2:-$root/../shared/data/textured/spot/cow.obj}
out=${3:-$(mktemp -d)}
[[ -f $mesh ]] || { echo "texture_weight: no mesh $mesh" >&2; exit 1; }
mkdir -p "$out"
cli=$build/tools/meshwave/meshwave
weights=${WEIGHTS:-1 0.01 0.001 0.0001 0.00001 0.000001}
budgets=${BUDGETS:-10000 20000 30000 50000 60000 90000}
views=${VIEWS:-30,20 210,10}
size=${SIZE:-600}
for v in $views; do
  "$cli" render --view "$v" --width "$size" --height "$size" "$mesh" "$out/original_$v.png" > /dev/null
done
printf 'weight\tbudget\tbytes\tvertices\ttexture\tdB per view\n'
for w in $weights; do
  "$cli" encode --texture-weight "$w" "$mesh" "$out/w$w.mwv" > /dev/null 2>&1
  total=$(stat -c %s "$out/w$w.mwv")
  for b in $budgets $total; do
    line=$("$cli" decode --budget "$b" "$out/w$w.mwv" "$out/d.glb" 2>&1 | tr '\n' ' ')
    vertices=$(sed -n 's/.*: \([0-9]*\) vertices.*/\1/p' <<< "$line")
    texture=$(grep -o 'base colour [0-9]* x [0-9]*' <<< "$line" | sed 's/base colour //' || true)
    bytes=$(sed -n 's/.* \([0-9]*\) bytes.*/\1/p' <<< "$line" | head -n 1)
    dbs=()
    for v in $views; do
      "$cli" render --view "$v" --width "$size" --height "$size" "$out/d.glb" "$out/d.png" > /dev/null
      dbs+=("$(python3 "$root/bench/render_psnr.py" "$out/original_$v.png" "$out/d.png")")
    done
    printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$w" "$b" "${bytes:-?}" "${vertices:-?}" "${texture:--}" "${dbs[*]}"
  done
done
