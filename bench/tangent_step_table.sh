#!/usr/bin/env bash
# The tangential step (EncodeOptions::tangent_step_scale, `encode
# --tangent-step S`) measured as users judge a stream: bytes of the smallest
# rd-order prefix whose decoded mesh reaches Draco's surface PSNR against the
# ORIGINAL mesh at qp 8, 10, 11 and 12 (`draco_encoder -cl 10`), for each S,
# on the same remesh of each mesh, plus each stream's size and ceiling (the
# complete stream's PSNR). Every PSNR is `meshwave compare`'s symmetric
# surface PSNR against the original.
#
# Usage: bench/tangent_step_table.sh [BUILD_DIR]   (needs draco, jq, bc)
#   MESHES="a.ply b.obj"   other meshes (default: shared ones >= 5 k vertices)
#   STEPS="1 2 4 8 16"     tangent step scales
#   QPS="8 10 11 12"       Draco points
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
cli=$build/tools/meshwave/meshwave
[[ -x $cli ]] || { echo "no meshwave binary at $cli (build first)" >&2; exit 1; }
source "$root/bench/lib.sh"
need_tools draco_encoder draco_decoder jq bc
shared=$root/../shared/data/meshes
list=${MESHES:-$(shared_meshes_of_at_least 5000)}
steps=${STEPS:-1 2 4 8 16}
qps=${QPS:-8 10 11 12}
tmp=$(mktemp -d)
cache=$tmp
trap 'rm -rf "$tmp"' EXIT

header="| mesh | step | stream bytes | ceiling dB |"
rule="|---|---|---|---|"
for qp in $qps; do header="$header qp $qp: prefix bytes (ratio) |"; rule="$rule---|"; done
echo "$header"; echo "$rule"
for mesh in $list; do
  name=$(basename "$mesh")
  echo "$name: remeshing, Draco at qp $qps" >&2
  meshes=$(dirname "$mesh")
  sr=$(semi_regular "$name")  # the remesh every step encodes (as `encode` would make it)
  declare -A dbytes=() dpsnr=()
  for qp in $qps; do
    draco_encoder -i "$mesh" -o "$tmp/d.drc" -cl 10 -qp "$qp" > /dev/null
    draco_decoder -i "$tmp/d.drc" -o "$tmp/d.ply" > /dev/null
    dbytes[$qp]=$(stat -c %s "$tmp/d.drc")
    dpsnr[$qp]=$(surface_psnr "$mesh" "$tmp/d.ply")
  done
  row="| $name | Draco | | |"
  for qp in $qps; do row="$row ${dbytes[$qp]} B, $(printf '%.2f' "${dpsnr[$qp]}") dB |"; done
  echo "$row"
  for s in $steps; do
    stream=$tmp/${name%.*}-$s.mwv
    "$cli" encode "$sr" "$stream" --tangent-step "$s" > /dev/null 2>&1
    "$cli" decode "$stream" "$tmp/full.ply" > /dev/null
    row="| $name | $s | $(stat -c %s "$stream") | $(printf '%.2f' "$(surface_psnr "$mesh" "$tmp/full.ply")") |"
    for qp in $qps; do
      read -r pb _ <<< "$(rd_prefix "$mesh" "$stream" "${dpsnr[$qp]}")"
      if [[ $pb == - ]]; then row="$row - |"
      else row="$row $pb ($(printf '%.2f' "$(echo "$pb / ${dbytes[$qp]}" | bc -l)")x) |"; fi
    done
    echo "$row"
  done
done
