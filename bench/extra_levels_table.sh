#!/usr/bin/env bash
# How dense a decoded prefix needs to be (issue 17, "a denser finest level
# must not cost the clients who do not need it"). For each mesh: encode it
# at default settings, then at budgets of 5, 10, 20, 40 and 100 % of the
# stream (rd order) decode it with `--extra-levels` 0, 1, 2 and 12 (every
# level) and measure the decoded mesh's symmetric surface PSNR against the
# ORIGINAL mesh (`meshwave compare`, peak = the original's bounding-box
# diagonal). Prints a Markdown table: vertices and PSNR per setting.
#
# Usage: bench/extra_levels_table.sh [BUILD_DIR] [MESH...]
#   default meshes: bunny, horse and fandisk from ../shared/data/meshes
#   MESHWAVE_ENCODE_ARGS adds arguments to `meshwave encode` (e.g. "--levels 5")
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
shift || true
cli=$build/tools/meshwave/meshwave
[[ -x $cli ]] || { echo "no meshwave binary at $cli (build first)" >&2; exit 1; }
shared=$root/../shared/data/meshes
if (( $# == 0 )); then
  [[ -d $shared ]] || { echo "no shared meshes at $shared: name meshes on the command line" >&2; exit 1; }
  set -- "$shared/bunny_stanford_zipper.ply" "$shared/horse_cyberware.ply" "$shared/fandisk.obj"
fi
command -v jq > /dev/null || { echo "jq is needed (apt-get install jq)" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

echo "| mesh | budget (bytes) | detail levels / J | extra 0: vertices, dB | extra 1 (default) | extra 2 | every level |"
echo "|---|---|---|---|---|---|---|"
for mesh in "$@"; do
  name=$(basename "$mesh")
  echo "encoding $name" >&2
  # shellcheck disable=SC2086  # the arguments are words on purpose
  "$cli" encode "$mesh" "$tmp/s.mwv" ${MESHWAVE_ENCODE_ARGS:-} > /dev/null
  size=$(stat -c %s "$tmp/s.mwv")
  for pct in 5 10 20 40 100; do
    budget=$(( size * pct / 100 ))
    row="| $name | $budget ($pct %) |"
    detail=
    for extra in 0 1 2 12; do
      if ! "$cli" decode "$tmp/s.mwv" "$tmp/d.ply" --order rd --budget "$budget" \
        --extra-levels "$extra" --json > "$tmp/d.json" 2> "$tmp/err"; then
        row="$row $(cat "$tmp/err") |"; break
      fi
      psnr=$("$cli" compare "$mesh" "$tmp/d.ply" --json | jq '.surface.rms.psnr_db')
      [[ -z $detail ]] && detail="$(jq .level "$tmp/d.json") / $(jq .levels "$tmp/d.json")" &&
        row="$row $detail |"
      row="$row $(jq -r .vertices "$tmp/d.json"), $(printf %.2f "$psnr") |"
    done
    echo "$row"
  done
done
