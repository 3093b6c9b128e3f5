#!/usr/bin/env bash
# The region order against the uniform rd order (issue 21): each shared mesh
# encoded (`meshwave encode`, default settings plus $ENCODE_ARGS), then
# `meshwave region-rd` on the stream: spheres holding 5, 10 and 25 % of the
# finest vertices around the vertices farthest along two fixed directions;
# per sphere the region's PSNR at 10, 25 and 50 % of the payload bytes in
# both orders, and the bytes each needs before the region's vertices are
# exactly the complete stream's. PSNR: vertex PSNR of the vertices inside
# the sphere against the complete stream's decoded mesh, peak = the
# header's bounding-box diagonal.
#
# Usage: bench/region_table.sh [BUILD_DIR]
#   MESHES="a.ply b.obj"   other meshes (default: the shared ones)
#   ENCODE_ARGS="..."      e.g. "--precinct-size 1024"
#   SEEDS=2                spheres per share
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
cli=$build/tools/meshwave/meshwave
[[ -x $cli ]] || { echo "no meshwave binary at $cli (build first)" >&2; exit 1; }
source "$root/bench/lib.sh"
meshes=$(shared_meshes)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "# meshwave region-rd, encode options: ${ENCODE_ARGS:-(defaults)}"
for mesh in $meshes; do
  name=$(basename "${mesh%.*}")
  echo "$name: encoding" >&2
  # shellcheck disable=SC2086
  "$cli" encode ${ENCODE_ARGS:-} "$mesh" "$tmp/$name.mwv" > /dev/null 2>&1
  "$cli" region-rd --seeds "${SEEDS:-2}" "$tmp/$name.mwv"
done
