#!/usr/bin/env bash
# Texture against geometry in the quality order: a textured mesh encoded
# with several --texture-weight values, each decoded at a range of budgets
# and scored by `meshwave render-compare` against the original (luma PSNR
# over the object's pixels, 16 cameras, 2x2 samples a pixel). The weight
# that sends the texture levels where they pay most on screen is the
# encoder's default (EncodeOptions::texture_rd_weight).
#
# Usage: bench/texture_weight.sh [BUILD_DIR] [MESH] [OUT_DIR]
#   defaults: build, ../shared/data/textured/spot/cow.obj, a temporary directory
#   WEIGHTS="1 0.01 0.001 0.0001 0.00001 0.000001"  BUDGETS="4000 8000 12000 16000 24000 32000 48000"
#   VIEWS=16  SIZE=1024
set -euo pipefail
if [[ ${1:-} == -h || ${1:-} == --help ]]; then sed -n '2,13p' "$0" | sed 's/^# \{0,1\}//'; exit 0; fi
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
mesh=${2:-$root/../shared/data/textured/spot/cow.obj}
out=${3:-$(mktemp -d)}
[[ -f $mesh ]] || { echo "texture_weight: no mesh $mesh" >&2; exit 1; }
mkdir -p "$out"
cli=$build/tools/meshwave/meshwave
weights=${WEIGHTS:-1 0.01 0.001 0.0001 0.00001 0.000001}
budgets=${BUDGETS:-4000 8000 12000 16000 24000 32000 48000}
printf 'weight\tbudget\tbytes\tvertices\ttexture\tdB\n'
for w in $weights; do
  "$cli" encode --texture-weight "$w" "$mesh" "$out/w$w.mwv" > /dev/null 2>&1
  total=$(stat -c %s "$out/w$w.mwv")
  declare -A line=()
  files=()
  for b in $budgets $total; do
    (( b <= total )) || continue
    decoded=$out/w${w}_b$b.glb
    line[$decoded]=$("$cli" decode --budget "$b" "$out/w$w.mwv" "$decoded" 2>&1 | tr '\n' ' ')
    files+=("$decoded")
  done
  while IFS=$'\t' read -r db _ file; do
    text=${line[$file]}
    b=${file##*_b}; b=${b%.glb}
    vertices=$(sed -n 's/.*: \([0-9]*\) vertices.*/\1/p' <<< "$text")
    texture=$(grep -o 'base colour [0-9]* x [0-9]*' <<< "$text" | sed 's/base colour //' || true)
    bytes=$(sed -n 's/.* \([0-9]*\) bytes.*/\1/p' <<< "$text" | head -n 1)
    printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$w" "$b" "${bytes:-?}" "${vertices:-?}" "${texture:--}" "$db"
  done < <("$cli" render-compare --views "${VIEWS:-16}" --size "${SIZE:-1024}" "$mesh" "${files[@]}")
  unset line
done
